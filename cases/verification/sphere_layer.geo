// A quarter of an elastic layer, thickness 1 mm and radius 3 mm, for a rigid sphere pressed on
// the axis z (sphere_on_layer.toml). The layer spans z = 0 (top, touched by the sphere) to
// z = 1 mm (bottom, bonded to a rigid base). Millimetres. Physical groups: volume "tissue";
// surfaces "top", "base", "x0", "y0", "side". Elements of 0.025 mm over the contact (radius
// 0.1 mm), growing to 0.5 mm.
SetFactory("OpenCASCADE");
thickness = 1.0;
extent = 3.0;
eps = 1e-6;

Cylinder(1) = {0, 0, 0, 0, 0, thickness, extent, Pi / 2};

top_faces[] = Surface In BoundingBox {-eps, -eps, -eps, extent + eps, extent + eps, eps};
base_faces[] = Surface In BoundingBox {-eps, -eps, thickness - eps, extent + eps, extent + eps, thickness + eps};
x0[] = Surface In BoundingBox {-eps, -eps, -eps, eps, extent + eps, thickness + eps};
y0[] = Surface In BoundingBox {-eps, -eps, -eps, extent + eps, eps, thickness + eps};
side[] = Surface{:};
side[] -= {top_faces[], base_faces[], x0[], y0[]};
centre[] = Point In BoundingBox {-eps, -eps, -eps, eps, eps, eps};

Field[1] = Distance;
Field[1].PointsList = {centre[]};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.025;
Field[2].SizeMax = 0.5;
Field[2].DistMin = 0.15;
Field[2].DistMax = 1.5;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;

Physical Volume("tissue") = {1};
Physical Surface("top") = {top_faces[]};
Physical Surface("base") = {base_faces[]};
Physical Surface("x0") = {x0[]};
Physical Surface("y0") = {y0[]};
Physical Surface("side") = {side[]};
