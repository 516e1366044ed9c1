algebraic3d

# Conjugate heat transfer: an aluminium block (the heat sink, 20 x 10 x 20 mm)
# on the floor of a rectangular air channel (100 x 40 x 40 mm, y up); air
# enters at x = 0 and leaves at x = 0.1, the block is heated through its
# base. Two top-level solids, two regions: air (the channel without the
# block) and heatSink (the block); the faces between them (the block's
# sides and top) have no bcname: they are the interface.
# Netgen 6.2 names a surface by the first solid definition that gives it a
# -bcname, so each face is its own half-space (an orthobrick has one bcname
# for all six), and a bcname may not be a CSG keyword.

solid inletPlane  = plane (0, 0, 0; -1, 0, 0) -bcname=inlet;
solid outletPlane = plane (0.1, 0, 0; 1, 0, 0) -bcname=outlet;
solid floor       = plane (0, 0, 0; 0, -1, 0) -bcname=channelWalls;
solid ceiling     = plane (0, 0.04, 0; 0, 1, 0) -bcname=channelWalls;
solid zMin        = plane (0, 0, 0; 0, 0, -1) -bcname=channelWalls;
solid zMax        = plane (0, 0, 0.04; 0, 0, 1) -bcname=channelWalls;

# The block's base lies in the floor plane. Netgen merges identical planes
# into one surface, named after the first definition (channelWalls), so
# its -bcname below is ignored; boundaryconditionname at the end gives the
# part of that surface bounding heatSink a boundary condition (and a patch)
# of its own. (Using the solid "floor" itself for the base instead makes
# Netgen mesh the footprint twice: a non-manifold surface.)
solid blockBase   = plane (0, 0, 0; 0, -1, 0) -bcname=heaterBase;
solid blockXMin   = plane (0.03, 0, 0; -1, 0, 0);
solid blockXMax   = plane (0.05, 0, 0; 1, 0, 0);
solid blockTop    = plane (0, 0.01, 0; 0, 1, 0);
solid blockZMin   = plane (0, 0, 0.01; 0, 0, -1);
solid blockZMax   = plane (0, 0, 0.03; 0, 0, 1);
solid block       = blockBase and blockXMin and blockXMax and blockTop
                and blockZMin and blockZMax;

solid air = inletPlane and outletPlane and floor and ceiling and zMin and zMax
        and not block;
solid heatSink = block;

tlo air;
tlo heatSink;

boundaryconditionname blockBase heatSink heaterBase;
