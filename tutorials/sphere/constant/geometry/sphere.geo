algebraic3d

# The unit sphere of the PMSH paper (sphere.geo): one patch, "sphere"
solid ball = sphere (0, 0, 0; 1) -bcname=sphere;

tlo ball;
