algebraic3d
# A unit cube whose faces x = 0 and x = 1 are periodic
solid left   = plane (0, 0, 0; -1, 0, 0) -bcname=left;
solid right  = plane (1, 0, 0; 1, 0, 0) -bcname=right;
solid cube   = left and right
               and plane (0, 0, 0; 0, -1, 0) and plane (0, 1, 0; 0, 1, 0)
               and plane (0, 0, 0; 0, 0, -1) and plane (0, 0, 1; 0, 0, 1);
identify periodic left right;
tlo cube;
