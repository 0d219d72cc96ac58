// Quincke-type spinal needle tip (needle.kind = "cad"): a primary bevel at `alpha` to the axis and
// two back-bevel (lancet) facets at `lancet` to the axis, turned +-`psi` about the axis from the
// heel, all through the point. Millimetres, axis +z, rear face on z = 0, point towards +z.
// Parameters (edit, or copy the file):
r = 0.36;       // needle radius (22 G: 0.72 mm outer diameter)
alpha = 15;     // primary bevel angle to the axis, deg
lancet = 24;    // lancet facet angle to the axis, deg
psi = 110;      // azimuth of the lancet facets' normals from the heel side, deg
shaft = 0.1;    // straight shaft behind the heel
flat = 0.2;     // blunted point: a flat across the point where the bevel's section is this high
                // (0: sharp). The contact needle rounds every edge by needle.edge_radius_um (0.1 mm
                // by default), which takes a point this thin back to about where its section is 2
                // radii high; left sharp, the cavity's rounding moves the tissue there by 0.68 mm,
                // more than its elements allow (tests/mesh: sharp_point_over_rounded_...). The
                // lancets reach 0.47 mm back from the sharp point: a flat of 0.13 mm or more cuts
                // them off, so at the default edge radius this is a 15 deg bevel with a flat; the
                // lancets need edges of tens of µm (docs/accuracy.md §9).
SetFactory("OpenCASCADE");
deg = Pi / 180;
tip = shaft + 2 * r / Tan(alpha * deg);  // the point, on the generator x = -r
Cylinder(1) = {0, 0, 0, 0, 0, tip + 0.5, r};
// Each cut is the half-space above a plane: a box standing on z = const through its pivot, tilted
// about y to the plane's angle and turned about z to its azimuth.
Box(2) = {r - 5, -5, shaft, 10, 10, 10};
Rotate {{0, 1, 0}, {r, 0, shaft}, Pi / 2 - alpha * deg} { Volume{2}; }
Box(3) = {-r - 5, -5, tip, 10, 10, 10};
Rotate {{0, 1, 0}, {-r, 0, tip}, Pi / 2 - lancet * deg} { Volume{3}; }
Rotate {{0, 0, 1}, {-r, 0, tip}, psi * deg} { Volume{3}; }
Box(4) = {-r - 5, -5, tip, 10, 10, 10};
Rotate {{0, 1, 0}, {-r, 0, tip}, Pi / 2 - lancet * deg} { Volume{4}; }
Rotate {{0, 0, 1}, {-r, 0, tip}, -psi * deg} { Volume{4}; }
cuts[] = {2, 3, 4};
If (flat > 0)
  Box(5) = {-5, -5, tip - flat / Tan(alpha * deg), 10, 10, 10};
  cuts[] += 5;
EndIf
BooleanDifference(10) = { Volume{1}; Delete; }{ Volume{cuts[]}; Delete; };
