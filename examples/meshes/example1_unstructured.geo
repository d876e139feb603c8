// The paper's example 1 rectangle, 400 × 200 mm, meshed with unstructured 8-node quadrilaterals
// of size about 25 mm times Mesh.MeshSizeFactor: for the convergence of λ_c to the closed form (42) on meshes that
// are not a grid. The same groups as example1_rectangle.geo: edges `left`, `right`, `bottom`,
// `top`, points `centre` and `right_middle`, surface `membrane`.
// Remake: python3 examples/meshes/make_meshes.py (needs the `gmsh` Python package).
size = 25;
L = 400; W = 200;
Point(1) = {0, 0, 0, size};     Point(2) = {L/2, 0, 0, size};   Point(3) = {L, 0, 0, size};
Point(4) = {0, W/2, 0, size};   Point(5) = {L/2, W/2, 0, size}; Point(6) = {L, W/2, 0, size};
Point(7) = {0, W, 0, size};     Point(8) = {L/2, W, 0, size};   Point(9) = {L, W, 0, size};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 5}; Line(4) = {5, 6};
Line(5) = {7, 8}; Line(6) = {8, 9};
Line(7) = {1, 4}; Line(8) = {4, 7}; Line(9) = {2, 5}; Line(10) = {5, 8};
Line(11) = {3, 6}; Line(12) = {6, 9};
Curve Loop(1) = {1, 9, -3, -7};   Plane Surface(1) = {1};
Curve Loop(2) = {2, 11, -4, -9};  Plane Surface(2) = {2};
Curve Loop(3) = {3, 10, -5, -8};  Plane Surface(3) = {3};
Curve Loop(4) = {4, 12, -6, -10}; Plane Surface(4) = {4};
Recombine Surface{1, 2, 3, 4};
Physical Curve("left") = {7, 8};
Physical Curve("right") = {11, 12};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {5, 6};
Physical Point("centre") = {5};
Physical Point("right_middle") = {6};
Physical Surface("membrane") = {1, 2, 3, 4};
Mesh.Algorithm = 8;              // Frontal-Delaunay for quads
Mesh.RecombinationAlgorithm = 3; // Blossom, full-quad
Mesh.RecombineAll = 1;
Mesh.SubdivisionAlgorithm = 1;   // all quadrilaterals
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Mesh.MshFileVersion = 4.1;
