// An eighth of a thick-walled hollow sphere (inner radius 1 mm, outer 2 mm), with rollers on its
// three symmetry planes x0, y0, z0. Millimetres. Physical groups: volume "tissue"; surfaces
// "inner", "outer", "x0", "y0", "z0".
SetFactory("OpenCASCADE");
inner = 1.0;
outer = 2.0;
Mesh.MeshSizeMax = 0.25;
eps = 1e-6;

Sphere(1) = {0, 0, 0, outer, 0, Pi / 2, Pi / 2};
Sphere(2) = {0, 0, 0, inner, 0, Pi / 2, Pi / 2};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};

x0[] = Surface In BoundingBox {-eps, -eps, -eps, eps, outer + eps, outer + eps};
y0[] = Surface In BoundingBox {-eps, -eps, -eps, outer + eps, eps, outer + eps};
z0[] = Surface In BoundingBox {-eps, -eps, -eps, outer + eps, outer + eps, eps};
inside[] = Surface In BoundingBox {-eps, -eps, -eps, inner + eps, inner + eps, inner + eps};
sphere_faces[] = Surface{:};
sphere_faces[] -= {x0[], y0[], z0[], inside[]};

Physical Volume("tissue") = {3};
Physical Surface("x0") = {x0[]};
Physical Surface("y0") = {y0[]};
Physical Surface("z0") = {z0[]};
Physical Surface("inner") = {inside[]};
Physical Surface("outer") = {sphere_faces[]};
