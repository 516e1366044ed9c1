# pmshFoam test geometry: a stepped shaft along z.
# Thin section (radius 0.5) for 0 < z < 1.5, shoulder (radius 1) for
# 1.5 < z < 3. Boundary names go on solid definitions (-bcname=...): the
# first definition that names a surface wins.
algebraic3d

solid inletPlane  = plane(0, 0, 0; 0, 0, -1) -bcname=inlet;
solid outletPlane = plane(0, 0, 3; 0, 0, 1) -bcname=outlet;
solid step        = plane(0, 0, 1.5; 0, 0, 1) -bcname=shoulder;
solid thinWall    = cylinder(0, 0, -1; 0, 0, 4; 0.5) -bcname=shaftWall;
solid thickWall   = cylinder(0, 0, -1; 0, 0, 4; 1) -bcname=shoulderWall;

solid shaft = (thinWall and inletPlane and step)
           or (thickWall and outletPlane and not step);

tlo shaft;
