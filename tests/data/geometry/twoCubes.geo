algebraic3d
# Two unit cubes side by side: two regions (cellZones left and right)
# sharing the face x = 1
solid left = orthobrick (0, 0, 0; 1, 1, 1);
solid right = orthobrick (1, 0, 0; 2, 1, 1);
tlo left;
tlo right;
