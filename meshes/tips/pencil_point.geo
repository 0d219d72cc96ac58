// Pencil-point (Sprotte/Whitacre-type) tip with a side port (needle.kind = "cad"): a tangent
// ogive of length `point` closing the cylinder to a point on the axis, and a round side port of
// radius `port` on the -x side, its axis along x at `port_z`, reaching the needle's axis (the
// port of a hollow needle; the tissue fills it). Millimetres, axis +z, rear face on z = 0.
// Parameters (edit, or copy the file):
r = 0.45;        // needle radius (20 G: 0.9 mm outer diameter)
point = 1.2;     // length of the ogive point
shaft = 0.6;     // straight shaft between the rear face and the ogive
port = 0.2;      // radius of the side port
port_z = 0.35;   // height of the port's axis above the rear face
flat = 0.2;      // blunted point: a flat where the ogive has this diameter (0: sharp); see
                 // trocar.geo for why
SetFactory("OpenCASCADE");
R = (r * r + point * point) / (2 * r);  // the tangent ogive's arc radius, centre (r - R, shaft)
Point(1) = {0, 0, 0};
Point(2) = {r, 0, 0};
Point(3) = {r, 0, shaft};
Point(4) = {0, 0, shaft + point};
Point(5) = {r - R, 0, shaft};
Line(1) = {1, 2};
Line(2) = {2, 3};
Circle(3) = {3, 5, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Extrude {{0, 0, 1}, {0, 0, 0}, 2 * Pi} { Surface{1}; }
Cylinder(20) = {-r - 0.5, 0, port_z, r + 0.5, 0, 0, port};
cuts[] = {20};
If (flat > 0)
  // The ogive's half-angle at the point: tan = point / (R - r).
  Box(21) = {-5, -5, shaft + point - flat / 2 * (R - r) / point, 10, 10, 10};
  cuts[] += 21;
EndIf
BooleanDifference(30) = { Volume{1}; Delete; }{ Volume{cuts[]}; Delete; };
