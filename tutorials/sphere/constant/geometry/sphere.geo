algebraic3d

# The unit sphere of the PMSH paper (sphere.geo): one patch, "walls".
# (Not "wall": OpenFOAM puts every wall patch in a group "wall", and a
# patch of that name clashes with the group, with a warning.)
# (Netgen 6.2 quirk: a bcname may not be a CSG keyword, so not "sphere".)
solid ball = sphere (0, 0, 0; 1) -bcname=walls;

tlo ball;
