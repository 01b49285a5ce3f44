// A flanged bush: a plate with a boss, bored through, with two bolt holes.
SetFactory("OpenCASCADE");
Box(1) = {0.15, 0.25, 0.2, 0.7, 0.5, 0.15};
Cylinder(2) = {0.5, 0.5, 0.2, 0, 0, 0.55, 0.18};
BooleanUnion(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
Cylinder(4) = {0.5, 0.5, 0.1, 0, 0, 0.8, 0.09};
Cylinder(5) = {0.25, 0.5, 0.1, 0, 0, 0.4, 0.04};
Cylinder(6) = {0.75, 0.5, 0.1, 0, 0, 0.4, 0.04};
BooleanDifference(7) = {Volume{3}; Delete;}{Volume{4,5,6}; Delete;};
