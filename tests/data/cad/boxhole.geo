// boxhole.geo: a 2 x 1 x 0.5 box with a cylindrical through-hole of
// radius 0.25 along z, centred at (1, 0.5), for tests/common/test_cad.c.
// Exact volume: 2*1*0.5 - pi*0.25^2*0.5 = 1 - pi/32.
// Regenerate the STEP file with
//     gmsh -0 boxhole.geo -o boxhole.step
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 0.5};
Cylinder(2) = {1, 0.5, -0.1, 0, 0, 0.7, 0.25};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
