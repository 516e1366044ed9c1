algebraic3d
# Five solids: an oil tank holding a core bar that runs from wall to wall,
# two coils (tubes) round it with oil between, and a temperature sensor
solid core   = orthobrick (0, 0.7, 0.7; 4, 1.3, 1.3);
solid coilA  = cylinder (0, 1, 1; 4, 1, 1; 0.6) and not cylinder (0, 1, 1; 4, 1, 1; 0.48)
               and plane (1.0, 1, 1; -1, 0, 0) and plane (1.8, 1, 1; 1, 0, 0);
solid coilB  = cylinder (0, 1, 1; 4, 1, 1; 0.6) and not cylinder (0, 1, 1; 4, 1, 1; 0.48)
               and plane (2.2, 1, 1; -1, 0, 0) and plane (3.0, 1, 1; 1, 0, 0);
solid sensor = sphere (3.5, 1, 1.65; 0.2);
solid oil    = orthobrick (0, 0, 0; 4, 2, 2)
               and not core and not coilA and not coilB and not sensor;
tlo oil;
tlo core;
tlo coilA;
tlo coilB;
tlo sensor;
