algebraic3d

# A straight pipe along x: diameter D = 1 (radius 0.5), length 14 D, from
# x = 0 (inlet) to x = 14 (outlet). The flow develops over the first 5-6 D
# at Re = 100 (entrance length about 0.06 Re D); the pressure drop is
# measured between x = 7 and x = 12, where it is Hagen-Poiseuille's.
# ("tube" is a CSG keyword, hence "barrel".)
# (Netgen 6.2 names a surface by the first solid definition that gives it
# a -bcname, so each surface is its own named solid.)

solid inletPlane  = plane (0, 0, 0; -1, 0, 0) -bcname=inlet;
solid outletPlane = plane (14, 0, 0; 1, 0, 0) -bcname=outlet;
solid barrel      = cylinder (-1, 0, 0; 15, 0, 0; 0.5) -bcname=walls;

solid pipe = barrel and inletPlane and outletPlane;

tlo pipe;
