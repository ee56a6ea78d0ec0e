// Unit square with named boundaries, the .geo counterpart of
// fsai::mesh::rectangle (used by the mesh tests to check .geo loading).
// Mesh size: ONELAB parameter fsai/h (set by fsai::mesh::from_geo_file).
DefineConstant[ h = {0.1, Name "fsai/h"} ];

Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Curve("left", 1) = {4};
Physical Curve("right", 2) = {2};
Physical Curve("bottom", 3) = {1};
Physical Curve("top", 4) = {3};
Physical Surface("domain", 1) = {1};
