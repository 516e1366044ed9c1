algebraic3d

# Flow past a sphere: a ball of diameter D = 1 at the origin in a box from
# x = -5 (inlet, 5 D upstream) to x = 15 (outlet, 15 D downstream) and
# 5 D to each side (blockage (pi/4)/100 = 0.8 %).
# Netgen 6.2 names a surface by the first solid definition that gives it a
# -bcname, so each face of the box is its own half-space (an orthobrick has
# one bcname for all six), and a bcname may not be a CSG keyword, so the
# sphere's patch is "ball", not "sphere".

solid inletPlane  = plane (-5, 0, 0; -1, 0, 0) -bcname=inlet;
solid outletPlane = plane (15, 0, 0; 1, 0, 0) -bcname=outlet;
solid yMin        = plane (0, -5, 0; 0, -1, 0) -bcname=sides;
solid yMax        = plane (0, 5, 0; 0, 1, 0) -bcname=sides;
solid zMin        = plane (0, 0, -5; 0, 0, -1) -bcname=sides;
solid zMax        = plane (0, 0, 5; 0, 0, 1) -bcname=sides;
solid ball        = sphere (0, 0, 0; 0.5) -bcname=ball;

solid fluid = inletPlane and outletPlane and yMin and yMax and zMin and zMax
          and not ball;

tlo fluid;
