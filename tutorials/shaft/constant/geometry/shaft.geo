algebraic3d

# A shaft along x: a journal of radius 0.5 from x = 0 to x = 4 with a
# shoulder of radius 0.8 between x = 1.5 and x = 2.5. The end faces are the
# inlet and outlet of a flow through it; the rest is wall.
# (Netgen 6.2 names a surface by the first solid definition that gives it
# a -bcname, so each surface is its own named solid.)

solid inletPlane     = plane (0, 0, 0; -1, 0, 0) -bcname=inlet;
solid outletPlane    = plane (4, 0, 0; 1, 0, 0) -bcname=outlet;
solid journal        = cylinder (-1, 0, 0; 5, 0, 0; 0.5) -bcname=walls;
solid shoulder       = cylinder (-1, 0, 0; 5, 0, 0; 0.8) -bcname=walls;
solid shoulderStart  = plane (1.5, 0, 0; -1, 0, 0) -bcname=walls;
solid shoulderEnd    = plane (2.5, 0, 0; 1, 0, 0) -bcname=walls;

solid shaft = (journal and inletPlane and outletPlane)
           or (shoulder and shoulderStart and shoulderEnd);

tlo shaft;
