// A block with a round hole, standing on the rigid foundation y = 0: the example of
// the book's page "A body of your own" (book/src/body.md).
//
//   gmsh -2 -format msh41 tools/meshes/holed_block.geo -o data/meshes/holed_block.msh
//
// The block is the paper's rectangle (0,2) x (0,1); the hole, of radius 0.25, is
// centred at (1, 0.5). Its named parts (physical curves) are what the scenario
// data/scenarios/examples/holed_block.toml refers to.

h = 0.08;      // the target edge length
r = 0.25;      // the hole's radius

// The outline, counter-clockwise from the lower-left corner. The sides are cut at
// y = 0.5 so that their upper halves can be clamped, as in the paper.
Point(1) = {0, 0, 0, h};
Point(2) = {2, 0, 0, h};
Point(3) = {2, 0.5, 0, h};
Point(4) = {2, 1, 0, h};
Point(5) = {0, 1, 0, h};
Point(6) = {0, 0.5, 0, h};
Line(1) = {1, 2};   // the bottom, on the foundation
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};   // the top
Line(5) = {5, 6};
Line(6) = {6, 1};

// The hole: four quarter circles about its centre.
Point(7) = {1, 0.5, 0, h};
Point(8) = {1 + r, 0.5, 0, h};
Point(9) = {1, 0.5 + r, 0, h};
Point(10) = {1 - r, 0.5, 0, h};
Point(11) = {1, 0.5 - r, 0, h};
Circle(7) = {8, 7, 9};
Circle(8) = {9, 7, 10};
Circle(9) = {10, 7, 11};
Circle(10) = {11, 7, 8};

Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Curve Loop(2) = {7, 8, 9, 10};
Plane Surface(1) = {1, 2};

// The parts the scenario names.
Physical Curve("base") = {1};          // the contact part, on y = 0
Physical Curve("clamped") = {3, 5};    // the sides' upper halves
Physical Curve("top") = {4};           // loaded
Physical Curve("hole") = {7, 8, 9, 10};
Physical Curve("lower_sides") = {2, 6};
Physical Surface("body") = {1};

Mesh.MshFileVersion = 4.1;
