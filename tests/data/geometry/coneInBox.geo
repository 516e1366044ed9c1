# pmshFoam test geometry: a sharp cone in a box (issue #24, sharp tips):
# the cone runs along x from its base (radius 0.3, x = -1) to a tip of
# radius 0.0005 at x = 0.8 (half angle 9.5 degrees), in the box
# [-2,2] x [-1,1]^2. Patches outer and body. (A tip of radius 0, cut by
# a plane through the apex, is refused by Netgen's surface mesher; and
# "cone" cannot be a bcname: it is a Netgen keyword.)
algebraic3d

solid outer = orthobrick (-2, -1, -1; 2, 1, 1) -bcname=outer;
solid body = cone (-1, 0, 0; 0.3; 0.8, 0, 0; 0.0005)
    and plane (-1, 0, 0; -1, 0, 0)
    and plane (0.8, 0, 0; 1, 0, 0) -bcname=body;

solid fluid = outer and not body;

tlo fluid;
