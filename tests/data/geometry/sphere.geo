# pmshFoam test geometry: unit sphere (radius 1, centred at the origin).
# (A bcname cannot be a Netgen keyword or primitive name: -bcname=sphere
# is a syntax error.)
algebraic3d

solid ball = sphere(0, 0, 0; 1) -bcname=wall;

tlo ball;
