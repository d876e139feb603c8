// An annulus, inner radius a = 75 mm, outer radius b = 150 mm, centred at the origin, meshed
// with 8-node quadrilaterals on a polar grid: `nc` elements per quarter turn around, `nr`
// across, the radial sizes growing geometrically (ratio `grow` per element) away from the
// inner rim, where the hoop compression of the Lamé state is largest. Physical groups: the
// curves `inner` and `outer`, the surface `membrane`.
// Remake: python3 examples/meshes/make_meshes.py (needs the `gmsh` Python package).
If (!Exists(a)) a = 75; EndIf
b = 150;
If (!Exists(nc)) nc = 24; EndIf
If (!Exists(nr)) nr = 12; EndIf
If (!Exists(grow)) grow = 1.08; EndIf
Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};  Point(3) = {0, a, 0};  Point(4) = {-a, 0, 0};  Point(5) = {0, -a, 0};
Point(6) = {b, 0, 0};  Point(7) = {0, b, 0};  Point(8) = {-b, 0, 0};  Point(9) = {0, -b, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};
Curve Loop(1) = {9, 5, -10, -1};  Plane Surface(1) = {1};
Curve Loop(2) = {10, 6, -11, -2}; Plane Surface(2) = {2};
Curve Loop(3) = {11, 7, -12, -3}; Plane Surface(3) = {3};
Curve Loop(4) = {12, 8, -9, -4};  Plane Surface(4) = {4};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8} = nc + 1;
Transfinite Curve{9, 10, 11, 12} = nr + 1 Using Progression grow;
Transfinite Surface{1, 2, 3, 4};
Recombine Surface{1, 2, 3, 4};
Physical Curve("inner") = {1, 2, 3, 4};
Physical Curve("outer") = {5, 6, 7, 8};
Physical Surface("membrane") = {1, 2, 3, 4};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Mesh.MshFileVersion = 4.1;
