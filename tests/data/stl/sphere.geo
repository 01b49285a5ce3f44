// Sphere of radius 0.3 at (0.5 0.5 0.5), triangulated by gmsh for the
// cutCells STL tests:  gmsh -2 sphere.geo -clmax 0.04 -o sphere.stl -format stl -bin
SetFactory("OpenCASCADE");
Sphere(1) = {0.5, 0.5, 0.5, 0.3};
