// A quarter of an elastic layer, thickness 2 mm and radius 6 mm, under a rigid flat-ended punch of
// radius 0.5 mm on the axis z (the needle obstacle of punch_on_layer.toml, whose flat end sits at
// z = 0.5 mm). The layer spans z = 0.5 to 2.5 mm; its top face touches the punch, its bottom is
// bonded to a rigid base. Millimetres. Physical groups: volume "tissue"; surfaces "top", "base",
// "x0", "y0", "side". Elements of 0.04 mm along the punch's rim, growing to 0.6 mm.
SetFactory("OpenCASCADE");
punch = 0.5;
thickness = 2.0;
extent = 6.0;
top = 0.5;
eps = 1e-6;

Cylinder(1) = {0, 0, top, 0, 0, thickness, punch, Pi / 2};
Cylinder(2) = {0, 0, top, 0, 0, thickness, extent, Pi / 2};
BooleanFragments{Volume{1, 2}; Delete;}{}
volumes[] = Volume{:};

top_faces[] = Surface In BoundingBox {-eps, -eps, top - eps, extent + eps, extent + eps, top + eps};
base_faces[] = Surface In BoundingBox {-eps, -eps, top + thickness - eps, extent + eps, extent + eps, top + thickness + eps};
x0[] = Surface In BoundingBox {-eps, -eps, top - eps, eps, extent + eps, top + thickness + eps};
y0[] = Surface In BoundingBox {-eps, -eps, top - eps, extent + eps, eps, top + thickness + eps};
inside[] = Surface In BoundingBox {-eps, -eps, top - eps, punch + eps, punch + eps, top + thickness + eps};
side[] = Surface{:};
side[] -= {top_faces[], base_faces[], x0[], y0[], inside[]};
rim[] = Curve In BoundingBox {-eps, -eps, top - eps, punch + eps, punch + eps, top + eps};

Field[1] = Distance;
Field[1].CurvesList = {rim[]};
Field[1].NNodesByEdge = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.04;
Field[2].SizeMax = 0.6;
Field[2].DistMin = 0.04;
Field[2].DistMax = 2.0;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;

Physical Volume("tissue") = {volumes[]};
Physical Surface("top") = {top_faces[]};
Physical Surface("base") = {base_faces[]};
Physical Surface("x0") = {x0[]};
Physical Surface("y0") = {y0[]};
Physical Surface("side") = {side[]};
