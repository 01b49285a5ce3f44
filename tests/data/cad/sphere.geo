// sphere.geo: unit sphere (radius 1, centred at the origin) for
// tests/common/test_cad.c.  Regenerate the STEP file with
//     gmsh -0 sphere.geo -o sphere.step
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
