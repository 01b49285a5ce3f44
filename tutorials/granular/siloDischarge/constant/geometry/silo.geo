// siloDischarge: the silo as a CAD part (gmsh's OpenCASCADE kernel), the
// flow domain itself, in metres, axis along y:
//   the silo     a cylinder of radius 0.2 from y = 0.70 to y = 1.00,
//   the hopper   a cone from radius 0.2 at y = 0.70 down to the orifice,
//                radius D/2 = 0.05 at y = 0.44 (walls 60.0 degrees from
//                the horizontal: tan = 0.26 / 0.15),
//   the bin      a closed box 1 x 0.44 x 1 below it (|x|, |z| <= 0.5,
//                0 <= y <= 0.44), which the orifice opens into.
// One solid, the union of the three; cutCells (shape cad) opens this file
// through gmsh's C API and triangulates its surfaces.  The 2-D tutorial
// takes its section with the plane z = 0: a slot hopper of width 0.4 with
// an orifice 0.1 wide over a bin 1 x 0.44.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0.70, 0, 0, 0.30, 0, 0.2};
Cone(2) = {0, 0.44, 0, 0, 0.26, 0, 0.05, 0.2};
Box(3) = {-0.5, 0, -0.5, 1, 0.44, 1};
BooleanUnion(4) = {Volume{1}; Delete;}{Volume{2, 3}; Delete;};
