// A block 1 x 1 x 0.5 mm (x, y, z) standing on the plane z = 0. Millimetres. Physical groups:
// volume "tissue"; surfaces "bottom" (z = 0), "top" (z = 0.5), "sides" (the other four).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Mesh.MeshSizeMax = 0.25;
eps = 1e-6;
bottom[] = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
top[] = Surface In BoundingBox {-eps, -eps, 0.5 - eps, 1 + eps, 1 + eps, 0.5 + eps};
sides[] = Surface{:};
sides[] -= {bottom[], top[]};
Physical Volume("tissue") = {1};
Physical Surface("bottom") = {bottom[]};
Physical Surface("top") = {top[]};
Physical Surface("sides") = {sides[]};
