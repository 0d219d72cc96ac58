// A quarter of a thick-walled tube (inner radius 1 mm, outer 2 mm) as a slice 0.2 mm long,
// for plane strain: rollers on the symmetry planes x0, y0 and on both end faces z0, z1.
// Millimetres. Physical groups: volume "tissue"; surfaces "inner", "outer", "x0", "y0", "z0", "z1".
inner = 1.0;
outer = 2.0;
length = 0.2;
Mesh.MeshSizeMax = 0.15;

Point(1) = {0, 0, 0};
Point(2) = {inner, 0, 0};
Point(3) = {outer, 0, 0};
Point(4) = {0, outer, 0};
Point(5) = {0, inner, 0};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// extruded[0]: the far end, [1]: the volume, [2..5]: the sides swept by curves 1..4.
extruded[] = Extrude {0, 0, length} { Surface{1}; };

Physical Volume("tissue") = {extruded[1]};
Physical Surface("z0") = {1};
Physical Surface("z1") = {extruded[0]};
Physical Surface("y0") = {extruded[2]};
Physical Surface("outer") = {extruded[3]};
Physical Surface("x0") = {extruded[4]};
Physical Surface("inner") = {extruded[5]};
