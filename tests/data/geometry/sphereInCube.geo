algebraic3d
# A ball in a cube: two regions (box and ball), the ball not touching
# the outer boundary
solid ball = sphere (0, 0, 0; 0.5);
solid box = orthobrick (-1, -1, -1; 1, 1, 1) and not ball;
tlo box;
tlo ball;
