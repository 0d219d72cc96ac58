// Three-facet trocar tip (needle.kind = "cad"): three plane facets at `alpha` to the axis, 120 deg
// apart, meeting in a point on the axis. Millimetres, axis +z, rear face on z = 0.
// Parameters (edit, or copy the file):
r = 0.5;        // needle radius
alpha = 20;     // facet angle to the axis, deg
shaft = 0.1;    // straight shaft behind the facets' heels
flat = 0.2;     // blunted point: a flat across the facets where their inscribed circle has this
                // diameter (0: sharp). The contact needle rounds every edge by needle.edge_radius_um
                // (0.1 mm by default), so a sharper point is not the needle in contact
                // (docs/accuracy.md §9).
SetFactory("OpenCASCADE");
deg = Pi / 180;
tip = shaft + r / Tan(alpha * deg);  // the point, on the axis
Cylinder(1) = {0, 0, 0, 0, 0, tip + 0.5, r};
// Each facet: the half-space above a plane through the point, tilted about y to `alpha` and
// turned about the axis to its azimuth.
For k In {0 : 2}
  Box(2 + k) = {-5, -5, tip, 10, 10, 10};
  Rotate {{0, 1, 0}, {0, 0, tip}, Pi / 2 - alpha * deg} { Volume{2 + k}; }
  Rotate {{0, 0, 1}, {0, 0, tip}, k * 2 * Pi / 3} { Volume{2 + k}; }
EndFor
cuts[] = {2, 3, 4};
If (flat > 0)
  Box(5) = {-5, -5, tip - flat / 2 / Tan(alpha * deg), 10, 10, 10};
  cuts[] += 5;
EndIf
BooleanDifference(10) = { Volume{1}; Delete; }{ Volume{cuts[]}; Delete; };
