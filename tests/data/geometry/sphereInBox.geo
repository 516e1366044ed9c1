# pmshFoam test geometry: external flow around a sphere of radius 0.5 in the
# box [-5,5]^3, the CSG twin of sphereInBox.stl: patches inlet (x = -5),
# outlet (x = 5), sides and body.
# (Netgen 6.2 names a surface by the first solid definition that gives it
# a -bcname, so each named surface is its own solid.)
algebraic3d

solid inletPlane  = plane (-5, 0, 0; -1, 0, 0) -bcname=inlet;
solid outletPlane = plane (5, 0, 0; 1, 0, 0) -bcname=outlet;
solid sides       = plane (0, -5, 0; 0, -1, 0)
                and plane (0, 5, 0; 0, 1, 0)
                and plane (0, 0, -5; 0, 0, -1)
                and plane (0, 0, 5; 0, 0, 1) -bcname=sides;
solid ball        = sphere (0, 0, 0; 0.5) -bcname=body;

solid fluid = inletPlane and outletPlane and sides and not ball;

tlo fluid;
