algebraic3d
# A unit cube periodic in x, y and z: three pairs of sides, which touch
# each other along the cube's edges and at its corners
solid left   = plane (0, 0, 0; -1, 0, 0) -bcname=left;
solid right  = plane (1, 1, 1; 1, 0, 0) -bcname=right;
solid front  = plane (0, 0, 0; 0, -1, 0) -bcname=front;
solid back   = plane (1, 1, 1; 0, 1, 0) -bcname=back;
solid bottom = plane (0, 0, 0; 0, 0, -1) -bcname=bottom;
solid top    = plane (1, 1, 1; 0, 0, 1) -bcname=top;
solid cube   = left and right and front and back and bottom and top;
identify periodic left right;
identify periodic front back;
identify periodic bottom top;
tlo cube;
