"""Render a run's running-maximum log strain (cell field max_over_time_log_strain at the last
output time) on a cut plane through the needle axis, headless, to PNG.

usage: xvfb-run -a pvbatch postprocess/render_max_strain.py RUN_DIR/result.xdmf [--png OUT.png]
           [--field NAME] [--normal x|y|z] [--offset-mm D] [--window-mm W] [--max V] [--size W H]
           [--mark-mm X Y Z [--mark-radius-mm R]]
(default OUT.png: result_max_log_strain.png next to the XDMF; /usr/bin/python3 with Debian's
python3-paraview also runs it, under xvfb-run.)

The default plane y = 0 holds the needle axis (z) and the bevel's side profile (x-z) of the
brain-tip scene (a block, which does not contain y = 0 inside, is cut through its middle). Tissue
cells are coloured by the field, the needle's cells (region "needle", when meshed) grey. The
view is parallel, insertion axis to the right, `--window-mm` wide around the needle tip
(default: three tip lengths when the needle is meshed, else the whole cut). Colour range 0 .. max of the field unless --max is given.
A scale bar under the field gives lengths in millimetres (a round length near a quarter of the
field's width); the script's last line states it and where it is drawn, in pixels.
--mark-mm draws, in red, where the ball of radius --mark-radius-mm (default 0.25, the critical
distance) centred at X Y Z (reference position, mm) meets the plane: the spot a critical-distance
value averages over (postprocess/study_report.py marks each limit's worst spot with it).
"""
import argparse
import os
import sys

from paraview.simple import (Clip, ColorBy, CreateView, GetColorTransferFunction, GetScalarBar, Ruler, Show, Slice,
                             SaveScreenshot, Sphere, Text, Threshold, Xdmf3ReaderS)

NORMALS = {"x": [1.0, 0.0, 0.0], "y": [0.0, 1.0, 0.0], "z": [0.0, 0.0, 1.0]}
# Camera direction and up vector per plane normal: insertion axis z to the right where it lies in the plane.
CAMERAS = {"x": ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), "y": ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
           "z": ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0])}


def information(xdmf, name):
    """The Value of the XDMF's Information element `name`, or None."""
    with open(xdmf) as f:
        for line in f:
            if f'Name="{name}"' in line:
                return line.split('Value="', 1)[1].split('"', 1)[0]
    return None


def region_names(xdmf):
    """Region index -> name from the XDMF's Information "region_names" ("0=tissue_core, ...")."""
    value = information(xdmf, "region_names")
    return {int(k): v for k, v in (item.strip().split("=", 1) for item in value.split(","))} if value else {}


def region_filter(source, low, high):
    selection = Threshold(Input=source)
    selection.Scalars = ["CELLS", "region"]
    selection.LowerThreshold = low
    selection.UpperThreshold = high
    return selection


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("xdmf")
    parser.add_argument("--png")
    parser.add_argument("--field", default="max_over_time_log_strain")
    parser.add_argument("--normal", choices=sorted(NORMALS), default="y")
    parser.add_argument("--offset-mm", type=float,
                        help="plane position along its normal (default 0, the needle axis, when inside the "
                             "tissue, else the middle of the tissue)")
    parser.add_argument("--window-mm", type=float, help="width of the view around the needle tip")
    parser.add_argument("--max", type=float, help="upper end of the colour range")
    parser.add_argument("--size", type=int, nargs=2, default=[1200, 900])
    parser.add_argument("--mark-mm", type=float, nargs=3, help="centre of a ball to outline on the plane")
    parser.add_argument("--mark-radius-mm", type=float, default=0.25)
    args = parser.parse_args()

    xdmf = os.path.abspath(args.xdmf)  # ParaView's Xdmf3 reader fails on bare relative names
    png = args.png or os.path.join(os.path.dirname(xdmf), "result_max_log_strain.png")
    reader = Xdmf3ReaderS(FileName=[xdmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) or [0.0]
    reader.UpdatePipeline(times[-1])
    if args.field not in reader.CellData.keys():
        sys.exit(f"{xdmf}: no cell field '{args.field}' (fields: {', '.join(reader.CellData.keys())})")

    names = region_names(xdmf)
    needle = [k for k, v in names.items() if v == "needle"]
    tissue_regions = [k for k, v in names.items() if v != "needle"] or [0]
    axis = "xyz".index(args.normal)
    if args.offset_mm is None:
        low, high = reader.GetDataInformation().GetBounds()[2 * axis:2 * axis + 2]
        args.offset_mm = 0.0 if low < 0.0 < high else (low + high) / 2
    origin = [n * args.offset_mm for n in NORMALS[args.normal]]

    view = CreateView("RenderView")
    view.ViewSize = args.size
    view.ViewTime = times[-1]
    view.OrientationAxesVisibility = 1
    view.OrientationAxesLabelColor = [0.0, 0.0, 0.0]
    view.UseColorPaletteForBackground = 0  # else the palette's background wins over Background
    view.Background = [1.0, 1.0, 1.0]
    view.CameraParallelProjection = 1

    tissue = region_filter(reader, min(tissue_regions), max(tissue_regions))
    cut = Slice(Input=tissue)
    cut.SliceType = "Plane"
    cut.SliceType.Origin = origin
    cut.SliceType.Normal = NORMALS[args.normal]
    cut.UpdatePipeline(times[-1])
    field_range = cut.CellData[args.field].GetRange()

    needle_length = 0.0
    if needle:
        needle_cut = Slice(Input=region_filter(reader, needle[0], needle[0]))
        needle_cut.SliceType = "Plane"
        needle_cut.SliceType.Origin = origin
        needle_cut.SliceType.Normal = NORMALS[args.normal]
        needle_cut.UpdatePipeline(times[-1])
        bounds = needle_cut.GetDataInformation().GetBounds()
        if bounds[0] <= bounds[1]:
            needle_length = bounds[5]

    # Frame the picture on the tissue: the field fills the lower left of the image, clipped to the
    # cut (no blank beside the entry face), with a band above for the title and one on the right
    # for the colour bar.
    direction, up = CAMERAS[args.normal]
    right = [up[1] * direction[2] - up[2] * direction[1], up[2] * direction[0] - up[0] * direction[2],
             up[0] * direction[1] - up[1] * direction[0]]  # up x (towards the viewer)
    h_axis, v_axis = right.index(max(right, key=abs)), up.index(1.0)
    flip = right[h_axis]  # +1: the axis grows to the right
    bounds = cut.GetDataInformation().GetBounds()
    aspect = args.size[1] / args.size[0]
    field_width, field_height = 0.80, 0.82  # fractions of the image the field fills
    ruler_band = 0.08  # under the field: the scale bar
    h_extent, v_extent = bounds[2 * h_axis + 1] - bounds[2 * h_axis], bounds[2 * v_axis + 1] - bounds[2 * v_axis]
    window = args.window_mm or (3.0 * needle_length if needle_length > 0 else h_extent)
    width = min(window, h_extent)  # world width of the field, then its height at the image's aspect
    height = width / field_width * aspect * field_height
    if height > v_extent:
        height = v_extent
        width = height / field_height / aspect * field_width
    view_width, view_height = width / field_width, height / field_height

    def place(axis, length, centre):
        """The field's interval along an axis: `length` long around `centre`, moved inside the cut."""
        low = min(max(centre - length / 2, bounds[2 * axis]), bounds[2 * axis + 1] - length)
        return low, low + length

    h_low, h_high = place(h_axis, width, needle_length / 2 if needle_length > 0 else sum(bounds[2 * h_axis:2 * h_axis + 2]) / 2)
    v_low, v_high = place(v_axis, height, origin[v_axis] if needle_length > 0 else sum(bounds[2 * v_axis:2 * v_axis + 2]) / 2)
    screen_left = min(flip * h_low, flip * h_high)
    centre = list(origin)
    centre[h_axis] = flip * (screen_left + view_width / 2)
    centre[v_axis] = v_low - ruler_band * view_height + view_height / 2
    def crop(source):
        """The framed part of a cut, shown in its place: the bands around it stay white."""
        box = Clip(Input=source)
        box.ClipType = "Box"
        box.ClipType.UseReferenceBounds = 0
        box.Exact = 1
        position = [low - 0.5 for low in bounds[0::2]]
        length = [high - low + 1.0 for low, high in zip(bounds[0::2], bounds[1::2])]
        for axis, low, high in ((h_axis, h_low, h_high), (v_axis, v_low, v_high)):
            position[axis], length[axis] = low, high - low
        box.ClipType.Position = position
        box.ClipType.Length = length
        return Show(box, view)

    cropped = crop(cut)
    ColorBy(cropped, ("CELLS", args.field))
    lut = GetColorTransferFunction(args.field)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(0.0, args.max if args.max is not None else max(field_range[1], 1e-12))
    cropped.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    if needle_length > 0:
        needle_shown = crop(needle_cut)
        ColorBy(needle_shown, None)
        needle_shown.DiffuseColor = needle_shown.AmbientColor = [0.55, 0.55, 0.55]

    if args.mark_mm:
        # The ball's circle on the plane, moved a little towards the camera so the cut does not hide it.
        ball = Sphere(Center=args.mark_mm, Radius=args.mark_radius_mm, ThetaResolution=96, PhiResolution=96)
        ring = Slice(Input=ball)
        ring.SliceType = "Plane"
        ring.SliceType.Origin = [o + 0.02 * args.mark_radius_mm * d for o, d in zip(origin, direction)]
        ring.SliceType.Normal = NORMALS[args.normal]
        ring_shown = Show(ring, view)
        ring_shown.DiffuseColor = ring_shown.AmbientColor = [0.85, 0.0, 0.0]
        ring_shown.LineWidth = 3.0
        ring_shown.Ambient, ring_shown.Diffuse = 1.0, 0.0  # flat red, unlit

    view.CameraFocalPoint = centre
    view.CameraPosition = [c + 100.0 * d for c, d in zip(centre, direction)]
    view.CameraViewUp = up
    view.CameraParallelScale = view_height / 2

    # Scale bar: 1, 2 or 5 x 10^k mm, the largest not above a quarter of the field's width, from
    # the field's left edge, in the middle of the band under it.
    ruler_mm = max(m * 10.0 ** k for k in range(-3, 4) for m in (1, 2, 5) if m * 10.0 ** k <= width / 4)
    ruler = Ruler()
    start, end = list(origin), list(origin)
    start[v_axis] = end[v_axis] = v_low - ruler_band * view_height / 2
    start[h_axis] = flip * (screen_left + 0.02 * view_width)
    end[h_axis] = start[h_axis] + flip * ruler_mm
    ruler.Point1, ruler.Point2 = start, end
    ruler_shown = Show(ruler, view)
    ruler_shown.AxisColor = ruler_shown.Color = [0.0, 0.0, 0.0]
    ruler_shown.AxisLineWidth = 3.0
    ruler_shown.LabelFormat = "%g mm"
    ruler_shown.FontSize = 14
    pixels_per_mm = args.size[0] / view_width
    ruler_pixels = (round(0.02 * args.size[0]), round(args.size[1] * (1 - ruler_band / 2)), ruler_mm * pixels_per_mm)

    unit = information(xdmf, f"unit:{args.field}") or "?"  # the writer states each field's unit
    bar.Title = f"{args.field.replace('_', ' ')} [{unit}]"
    bar.ComponentTitle = ""
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Vertical"
    bar.Position = [field_width + 0.04, 0.08]
    bar.ScalarBarLength = 0.75
    bar.TitleFontSize = bar.LabelFontSize = 14
    bar.RangeLabelFormat = "%-#.3g"

    title = Text(Text=f"{args.field.replace('_', ' ')} at t = {times[-1]:g} s, plane {args.normal} = {args.offset_mm:g} mm "
                      f"(max {field_range[1]:.4g}{'' if unit == '1' else ' ' + unit}); field {width:.3g} x {height:.3g} mm")
    title_shown = Show(title, view)
    title_shown.Color = [0.0, 0.0, 0.0]
    title_shown.FontSize = 14
    title_shown.WindowLocation = "Upper Center"
    SaveScreenshot(png, view, ImageResolution=args.size)
    print(f"wrote {png} ({args.field} max {field_range[1]:.6g} on the cut)")
    print("scale bar {:g} mm: from pixel x = {}, y = {}, {:.1f} pixels long".format(ruler_mm, *ruler_pixels))


if __name__ == "__main__":
    main()
