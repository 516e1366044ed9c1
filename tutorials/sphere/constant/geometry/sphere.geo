algebraic3d

# The unit sphere of the PMSH paper (sphere.geo): one patch, "wall".
# (Netgen 6.2 quirk: a bcname may not be a CSG keyword, so not "sphere".)
solid ball = sphere (0, 0, 0; 1) -bcname=wall;

tlo ball;
