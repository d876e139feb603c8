// The paper's example 1 rectangle, 400 × 200 mm, as the built-in structured mesh of
// `examples/scenes/clamped_biaxial.toml` (32 × 16 Q8 elements): the same nodes.
//
// Four transfinite quadrants of 16 × 8 elements, so that the centre and the middle of the right
// edge are mesh points. Physical groups: the edges `left`, `right`, `bottom`, `top`, the points
// `centre` and `right_middle` (the biaxial preset's supports), the surface `membrane`.
// Remake: python3 examples/meshes/make_meshes.py (needs the `gmsh` Python package).
DefineConstant[ nx = 32, ny = 16 ];
L = 400; W = 200;
Point(1) = {0, 0, 0};     Point(2) = {L/2, 0, 0};   Point(3) = {L, 0, 0};
Point(4) = {0, W/2, 0};   Point(5) = {L/2, W/2, 0}; Point(6) = {L, W/2, 0};
Point(7) = {0, W, 0};     Point(8) = {L/2, W, 0};   Point(9) = {L, W, 0};
// Horizontal lines (left to right), then vertical ones (bottom to top).
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 5}; Line(4) = {5, 6};
Line(5) = {7, 8}; Line(6) = {8, 9};
Line(7) = {1, 4}; Line(8) = {4, 7}; Line(9) = {2, 5}; Line(10) = {5, 8};
Line(11) = {3, 6}; Line(12) = {6, 9};
Curve Loop(1) = {1, 9, -3, -7};   Plane Surface(1) = {1};
Curve Loop(2) = {2, 11, -4, -9};  Plane Surface(2) = {2};
Curve Loop(3) = {3, 10, -5, -8};  Plane Surface(3) = {3};
Curve Loop(4) = {4, 12, -6, -10}; Plane Surface(4) = {4};
Transfinite Curve{1, 2, 3, 4, 5, 6} = nx/2 + 1;
Transfinite Curve{7, 8, 9, 10, 11, 12} = ny/2 + 1;
Transfinite Surface{1, 2, 3, 4};
Recombine Surface{1, 2, 3, 4};
Physical Curve("left") = {7, 8};
Physical Curve("right") = {11, 12};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {5, 6};
Physical Point("centre") = {5};
Physical Point("right_middle") = {6};
Physical Surface("membrane") = {1, 2, 3, 4};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Mesh.MshFileVersion = 4.1;
