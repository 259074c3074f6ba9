"""Renders the frames of an ipstep run (ipstep --frames=DIR) with ParaView.

  xvfb-run -a pvpython tools/render_frames.py DIR OUT.gif [options]
  xvfb-run -a pvpython tools/render_frames.py DIR OUT.png --time 0.12 [options]

DIR/run.pvd is read by ParaView's PVD reader: its blocks "body", "obstacles"
and, for a 3D elastic solid, "surface" (io/frame_writer.h). The body (a 3D
solid's surface, or with --clip the solid's tetrahedra cut by a plane through
its centre) is coloured by --color, with one colour range over the whole run
(so that colours mean the same in every frame) and a colour bar; obstacles are
grey; ParaView's depth buffer draws what is in front in front. The camera
looks at the bodies' box over the whole run from --azimuth and --elevation
(degrees; y is up, azimuth 0 looks along -z). A GIF has at most --max-frames
frames, evenly spaced over the run, assembled with Pillow; a PNG is the frame
at --time (default: the last).

Colour fields: speed (|velocity|, m/s), contact_force (|force|, N, with
contact), J, energy_density (Pa), von_mises_stress (Pa) (elastic solids), or
none. docs/paraview.md says how to install pvpython (Debian: paraview,
python3-paraview) and xvfb-run (xvfb). Exit code 2 for bad input, 3 when
ParaView or Pillow is missing.
"""
import argparse
import math
import os
import sys
import tempfile
import xml.etree.ElementTree as ET

FIELDS = {  # name: (association, array, component, title)
    "speed": ("POINTS", "velocity", "Magnitude", "speed [m/s]"),
    "contact_force": ("POINTS", "contact_force", "Magnitude", "contact force [N]"),
    "J": ("CELLS", "J", None, "J = det F"),
    "energy_density": ("CELLS", "energy_density", None, "energy density [Pa]"),
    "von_mises_stress": ("CELLS", "von_mises_stress", None, "von Mises stress [Pa]"),
}


def fail(message, code=2):
    print(f"render_frames.py: error: {message}", file=sys.stderr)
    sys.exit(code)


def read_series(directory):
    """The frame times and the block names of DIR/run.pvd."""
    pvd = os.path.join(directory, "run.pvd")
    try:
        root = ET.parse(pvd).getroot()
    except (OSError, ET.ParseError) as e:
        fail(f"{pvd}: {e} (write frames with ipstep --frames={directory})")
    times, names = set(), set()
    for dataset in root.iter("DataSet"):
        times.add(float(dataset.get("timestep")))
        names.add(dataset.get("name", ""))
    if not times:
        fail(f"{pvd}: lists no frames")
    if "body" not in names:
        fail(f"{pvd}: no block named 'body' (frames of an older ipstep: write them again)")
    return pvd, sorted(times), names


def pick(times, max_frames):
    if len(times) <= max_frames:
        return times
    step = (len(times) - 1) / (max_frames - 1)
    return [times[round(i * step)] for i in range(max_frames)]


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", help="the --frames directory of an ipstep run")
    parser.add_argument("output", help="OUT.gif (the run) or OUT.png (one frame)")
    parser.add_argument("--color", default="speed", choices=sorted(FIELDS) + ["none"])
    parser.add_argument("--range", type=float, nargs=2, metavar=("LOW", "HIGH"),
                        help="colour range (default: the field's range over the run)")
    parser.add_argument("--time", type=float, help="PNG: the frame at this time [s]")
    parser.add_argument("--max-frames", type=int, default=60)
    parser.add_argument("--fps", type=float, default=15)
    parser.add_argument("--size", type=int, nargs=2, default=[480, 360], metavar=("W", "H"))
    parser.add_argument("--azimuth", type=float, default=30.0)
    parser.add_argument("--elevation", type=float, default=25.0)
    parser.add_argument("--zoom", type=float, default=1.0, help="> 1 comes closer")
    parser.add_argument("--clip", action="store_true",
                        help="cut a 3D solid by the plane z = its centre, showing its inside")
    parser.add_argument("--edges", action="store_true", help="draw the body's element edges")
    args = parser.parse_args()
    extension = os.path.splitext(args.output)[1].lower()
    if extension not in (".gif", ".png"):
        fail(f"{args.output}: the output must be a .gif or .png file")
    if args.max_frames < 2 or not args.fps > 0 or min(args.size) < 16 or not args.zoom > 0:
        fail("--max-frames must be >= 2, --fps and --zoom > 0, --size at least 16 x 16")
    return args, extension


def main():
    args, extension = parse_args()
    pvd, times, names = read_series(args.directory)
    try:
        from paraview import simple as pv
        from paraview import servermanager
    except ImportError:
        fail("ParaView's Python modules are missing: run this with pvpython "
             "(Debian: apt install paraview python3-paraview xvfb; docs/paraview.md)", 3)
    try:
        from PIL import Image
    except ImportError:
        fail(f"Pillow is not installed for {sys.executable}: install python3-pil", 3)

    reader = pv.PVDReader(FileName=pvd)
    solid = "surface" in names
    body = pv.ExtractBlock(Input=reader, Selectors=["/Root/surface" if solid and not args.clip
                                                    else "/Root/body"])
    shown = pv.MergeBlocks(Input=body)
    if args.clip:
        if not solid:
            fail("--clip needs a 3D elastic solid (frames with a 'surface' block)")
        reader.UpdatePipeline(times[0])
        bounds = shown.GetDataInformation().GetBounds()
        shown = pv.Clip(Input=shown, ClipType="Plane", Crinkleclip=0)
        shown.ClipType.Origin = [0, 0, 0.5 * (bounds[4] + bounds[5])]
        shown.ClipType.Normal = [0, 0, 1]

    pv._DisableFirstRenderCameraReset()  # the camera below, not ParaView's fit
    view = pv.GetActiveViewOrCreate("RenderView")
    view.ViewSize = list(args.size)
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass

    display = pv.Show(shown, view)
    display.Representation = "Surface With Edges" if args.edges else "Surface"
    if args.edges:
        display.EdgeColor = [0.25, 0.25, 0.3]
    if "obstacles" in names:
        obstacles = pv.MergeBlocks(Input=pv.ExtractBlock(Input=reader,
                                                         Selectors=["/Root/obstacles"]))
        shape = pv.Show(obstacles, view)
        shape.ColorArrayName = ["POINTS", ""]
        shape.AmbientColor = shape.DiffuseColor = [0.78, 0.78, 0.78]

    # Colour range and camera box over the whole run (planes left out of the box).
    low, high = math.inf, -math.inf
    box = [math.inf, -math.inf] * 3
    for time in times:
        shown.UpdatePipeline(time)
        info = shown.GetDataInformation()
        b = info.GetBounds()
        for k in range(3):
            box[2 * k] = min(box[2 * k], b[2 * k])
            box[2 * k + 1] = max(box[2 * k + 1], b[2 * k + 1])
        if args.color != "none":
            association, array, component, _ = FIELDS[args.color]
            data = shown.PointData if association == "POINTS" else shown.CellData
            if array not in data.keys():
                fail(f"{pvd}: the body has no {association.lower()[:-1]} data '{array}' "
                     f"for --color={args.color}")
            r = data[array].GetRange(-1 if component == "Magnitude" else 0)
            low, high = min(low, r[0]), max(high, r[1])
    if args.color == "none":
        display.ColorArrayName = ["POINTS", ""]
        display.AmbientColor = display.DiffuseColor = [0.35, 0.6, 0.85]
    else:
        association, array, component, title = FIELDS[args.color]
        pv.ColorBy(display, (association, array, component) if component else
                   (association, array))
        lut = pv.GetColorTransferFunction(array)
        if args.range:
            low, high = args.range
        if args.color == "J":  # diverging about 1: compressed blue, stretched red
            spread = max(abs(low - 1.0), abs(high - 1.0), 1e-6)
            low, high = 1.0 - spread, 1.0 + spread
            lut.ApplyPreset("Cool to Warm", True)
        else:
            lut.ApplyPreset("Viridis (matplotlib)", True)
        lut.RescaleTransferFunction(low, high if high > low else low + 1e-12)
        lut.AutomaticRescaleRangeMode = "Never"
        bar = pv.GetScalarBar(lut, view)
        bar.Title, bar.ComponentTitle = title, ""
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        bar.TitleFontSize = bar.LabelFontSize = 12
        bar.WindowLocation = "Any Location"
        bar.Position, bar.ScalarBarLength = [0.82, 0.12], 0.7
        bar.RangeLabelFormat = bar.LabelFormat = "%-#6.3g"
        bar.AddRangeLabels = 1
        bar.Orientation = "Vertical"
        display.SetScalarBarVisibility(view, True)

    clock = pv.Text(Text="")
    clock_display = pv.Show(clock, view)
    clock_display.Color = [0, 0, 0]
    clock_display.FontSize = 13
    clock_display.WindowLocation = "Upper Left Corner"

    centre = [0.5 * (box[2 * k] + box[2 * k + 1]) for k in range(3)]
    radius = 0.5 * math.sqrt(sum((box[2 * k + 1] - box[2 * k]) ** 2 for k in range(3))) or 1.0
    a, e = math.radians(args.azimuth), math.radians(args.elevation)
    direction = [math.cos(e) * math.sin(a), math.sin(e), math.cos(e) * math.cos(a)]
    distance = 1.15 * radius / math.sin(math.radians(15)) / args.zoom  # view angle 30
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[k] + distance * direction[k] for k in range(3)]
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 30

    def render(time, path):
        view.ViewTime = time
        clock.Text = f"t = {time:.3f} s"
        pv.Render(view)
        pv.SaveScreenshot(path, view, ImageResolution=list(args.size))

    if extension == ".png":
        time = times[-1] if args.time is None else min(times, key=lambda t: abs(t - args.time))
        render(time, args.output)
        print(f"wrote {args.output}: t = {time:g} s")
        return
    chosen = pick(times, args.max_frames)
    with tempfile.TemporaryDirectory() as scratch:
        images = []
        for i, time in enumerate(chosen):
            path = os.path.join(scratch, f"{i:05d}.png")
            render(time, path)
            images.append(Image.open(path).convert("RGB").quantize(colors=128, dither=0))
        images[0].save(args.output, save_all=True, append_images=images[1:], loop=0,
                       duration=round(1000 / args.fps), optimize=True)
    print(f"wrote {args.output}: {len(chosen)} frames, t = {chosen[0]:g} to {chosen[-1]:g} s")


if __name__ == "__main__":
    main()
