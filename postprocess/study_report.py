#!/usr/bin/python3
"""A sweep's study report: one self-contained HTML page (images as data URIs, no scripts or fonts
from elsewhere) that a browser opens from disk.

usage: /usr/bin/python3 postprocess/study_report.py SWEEP_DIR [--out REPORT.html] [--bands PATH]
           [--design-grid G] [--rate-grid G] [--no-render]

SWEEP_DIR is the output of `needlefem sweep` (sweep.h5, sweep.csv, one folder per design point).
The page has
  - the table of designs: swept values, status, the verdict overall and per limit (the
    critical-distance value against the limit, run/safety_report.hpp), the point maxima beside
    them (mesh-dependent), and each limit's error band and band verdict where --bands has one;
  - the figures of postprocess/sweep_figures.py (`all`);
  - per limited metric, the design where it comes closest to its limit (critical-distance value
    over limit), where and when, and a picture of that metric's running maximum on the plane
    through the spot, the averaging ball drawn (postprocess/render_max_strain.py, pvbatch under
    xvfb-run; --no-render leaves the pictures out);
  - the settings: the sweep file, the base case and the grid of swept values;
  - the software that made the runs (summary.json "software": needlefem version and commit,
    PETSc, SUNDIALS, gmsh API, HDF5).
--bands PATH: the error bands of a three-level study, as `tests/benchmarks/bench_study.py --levels 3`
writes them (its OUT/study_bands.csv, or OUT itself) or `needlefem converge` folders (one, or a
folder of them); a band belongs to the sweep's design with the same swept values.
Default --out: SWEEP_DIR/report.html. A folder that is not a sweep, a completed point without its
summary.json or history.csv, or points not yet run stop it with one line naming the path.
"""
import argparse
import base64
import csv
import datetime
import html
import json
import math
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import matplotlib

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import sweep_figures  # noqa: E402
from sweep_figures import SAFETY_LIMITS, Sweep  # noqa: E402

RENDER_SCRIPT = pathlib.Path(__file__).resolve().parent / "render_max_strain.py"
# The running-maximum cell field (result.xdmf) that shows each limited metric.
RENDER_FIELDS = {"log_strain": "max_over_time_log_strain", "strain_rate_per_s": "max_over_time_strain_rate",
                 "stress_pa": "max_over_time_von_mises"}
UNITS = {"log_strain": "", "strain_rate_per_s": "1/s", "stress_pa": "Pa"}
SOFTWARE = (("needlefem", "needlefem"), ("commit", "commit"), ("petsc", "PETSc"), ("sundials", "SUNDIALS"),
            ("gmsh_api", "gmsh (API)"), ("hdf5", "HDF5"))


class ReportError(Exception):
    """Bad input: one line naming the path and the reason."""


def verdict_word(code):
    """Table verdict column (1 pass, 0 fail, -1 unknown) in words."""
    return {1: "pass", 0: "fail"}.get(int(code), "")


def number(value, unit=""):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    return f"{value:.4g}" + (f" {unit}" if unit else "")


def load_sweep(directory):
    """The sweep table with every completed point's summary; ReportError on anything missing."""
    directory = pathlib.Path(directory)
    if not directory.is_dir():
        raise ReportError(f"{directory}: not a directory (expected the output folder of `needlefem sweep`)")
    if not (directory / "sweep.h5").exists():
        raise ReportError(f"{directory}: not a sweep directory (no sweep.h5; `needlefem sweep SWEEP.toml --out "
                          f"{directory}` makes one)")
    try:
        sweep = Sweep(directory)
    except SystemExit as e:  # sweep_figures stops with one line
        raise ReportError(str(e)) from None
    pending = [sweep.table["point"][i] for i in range(sweep.rows) if sweep.table["status"][i] == "pending"]
    if pending:
        raise ReportError(f"{directory}: {len(pending)} of {sweep.rows} design points not run yet "
                          f"({', '.join(pending[:3])}{', ...' if len(pending) > 3 else ''}): run the sweep "
                          "again to finish them")
    summaries = {}
    for i in range(sweep.rows):
        if sweep.table["status"][i] not in ("completed", "failed"):
            continue
        run_dir = directory / sweep.table["point"][i]
        needed = ["summary.json"] + (["history.csv"] if sweep.table["status"][i] == "completed" else [])
        for name in needed:
            if not (run_dir / name).exists():
                raise ReportError(f"{run_dir / name}: missing (sweep.csv lists {sweep.table['point'][i]} as "
                                  f"{sweep.table['status'][i]})")
        try:
            summaries[i] = json.loads((run_dir / "summary.json").read_text())
        except json.JSONDecodeError as e:
            raise ReportError(f"{run_dir / 'summary.json'}: not JSON ({e})") from None
    return sweep, summaries


# --- error bands -------------------------------------------------------------------------------

def case_value(case, key):
    """The value of a dotted case key ("needle.radius_mm") in a resolved case, or None."""
    node = case
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def as_float(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def read_bands(path):
    """[(design name, {key: value}, {limit: band})] from a study_bands.csv, a folder holding one, a
    `needlefem converge` folder or a folder of them. band: {"low", "high", "verdict", "values", "behaviour"}."""
    path = pathlib.Path(path)
    if path.is_dir() and (path / "study_bands.csv").exists():
        path = path / "study_bands.csv"
    if path.is_file() and path.suffix == ".csv":
        return bands_from_csv(path)
    if path.is_file() and path.name == "converge.json":
        path = path.parent
    if path.is_dir():
        folders = [path] if (path / "converge.json").exists() else sorted(p.parent for p in path.glob("*/converge.json"))
        if folders:
            return [band for folder in folders for band in bands_from_converge(folder)]
    raise ReportError(f"{path}: no error bands (expected study_bands.csv or `needlefem converge` folders with "
                      "converge.json)")


def bands_from_csv(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if not reader.fieldnames or "metric" not in reader.fieldnames or "design" not in reader.fieldnames:
            raise ReportError(f"{path}: not a study_bands.csv (no design and metric columns)")
        keys = reader.fieldnames[reader.fieldnames.index("grid") + 1:reader.fieldnames.index("metric")]
        designs = {}
        for row in reader:
            name = row["design"]
            values, bands = designs.setdefault(name, ({k: row[k] for k in keys}, {}))
            limit = row["metric"].split(".")[1] if row["metric"].startswith("safety.") else None
            if limit is None or not row["metric"].endswith(".critical_distance"):
                continue
            levels = [float(v) for v in row["values"].split(" / ") if v.strip()]
            gci = as_float(row.get("gci_fine"))
            if not levels or gci is None:
                continue
            fine = levels[-1]  # the converge band: f_fine +- gci_fine |f_fine|
            bands[limit] = {"low": fine - gci * abs(fine), "high": fine + gci * abs(fine), "verdict": row["verdict"],
                            "values": levels, "behaviour": row.get("behaviour", "")}
    return [(name, values, bands) for name, (values, bands) in designs.items()]


def bands_from_converge(folder):
    report = json.loads((folder / "converge.json").read_text())
    case = None
    for summary in sorted(folder.glob("level_*/summary.json")):
        case = json.loads(summary.read_text()).get("case")
        break
    bands = {}
    for metric in report.get("metrics", []):
        name = metric.get("metric", "")
        if name.startswith("safety.") and name.endswith(".critical_distance") and metric.get("band"):
            bands[name.split(".")[1]] = {"low": metric["band"][0], "high": metric["band"][1],
                                         "verdict": metric.get("verdict") or "", "values": metric.get("values", []),
                                         "behaviour": metric.get("behaviour", "")}
    return [(folder.name, case, bands)]


def match_bands(sweep, band_designs):
    """Row index -> bands of the band design with the same swept values; and the unmatched design names."""
    matched, unmatched = {}, []
    for name, values, bands in band_designs:
        rows = []
        if values is not None:
            for i in range(sweep.rows):
                same = True
                for key in sweep.swept_keys:
                    mine = sweep.table[key][i]
                    theirs = as_float(case_value(values, key) if "." in key and key not in values else values.get(key))
                    if isinstance(mine, str):
                        theirs_text = case_value(values, key) if key not in values else values[key]
                        same = same and str(theirs_text).lower() == mine.lower()
                    else:
                        same = same and theirs is not None and math.isclose(float(mine), theirs, rel_tol=1e-9)
                rows += [i] if same else []
        for i in rows:
            matched[i] = bands
        if not rows:
            unmatched.append(name if values is not None else f"{name} (no level_*/summary.json to match by)")
    return matched, unmatched


# --- pictures ----------------------------------------------------------------------------------

def png_width(png):
    """Pixel width from the PNG header (a wide figure, e.g. a safety map of many panels, gets the page's width)."""
    return int.from_bytes(pathlib.Path(png).read_bytes()[16:20], "big")


def data_uri(png):
    return "data:image/png;base64," + base64.b64encode(pathlib.Path(png).read_bytes()).decode("ascii")


def render(run_dir, field, position_mm, radius_mm, png):
    """render_max_strain.py on the plane y = (the spot's y) with the averaging ball's circle; returns
    (ok, message). pvbatch under xvfb-run, retried (as tests/sweep/check_sweep.py does) because pvbatch
    now and then aborts creating its X window on a loaded machine."""
    if not shutil.which("pvbatch") or not shutil.which("xvfb-run"):
        return False, "not rendered: pvbatch or xvfb-run not found (scripts/setup.sh --tests installs them)"
    command = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "pvbatch", str(RENDER_SCRIPT),
               str(run_dir / "result.xdmf"), "--png", str(png), "--field", field, "--offset-mm", f"{position_mm[1]:.9g}",
               "--mark-mm", *(f"{x:.9g}" for x in position_mm), "--mark-radius-mm", f"{radius_mm:.9g}",
               "--size", "1000", "750"]
    for attempt in range(4):
        if attempt:
            time.sleep(3 * attempt)
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode == 0 and pathlib.Path(png).exists():
            return True, result.stdout.strip().splitlines()[0] if result.stdout.strip() else ""
    errors = [line for line in result.stderr.splitlines() if "INFO" not in line and line.strip()]
    return False, "not rendered: " + " | ".join(errors[-3:] or ["pvbatch failed"])


def worst_locations(sweep, summaries, work, do_render):
    """Per limit: the completed design closest to (or furthest over) the limit by its critical-distance
    value, with where and when, its point maximum, and a picture."""
    found = []
    for limit, words in SAFETY_LIMITS:
        candidates = [(s["safety"][limit]["critical_distance"]["value"] / s["safety"][limit]["limit"], i)
                      for i, s in summaries.items() if s.get("status") == "completed"
                      and limit in s.get("safety", {}) and "critical_distance" in s["safety"][limit]]
        if not candidates:
            continue
        ratio, i = max(candidates)
        entry = summaries[i]["safety"][limit]
        point = sweep.table["point"][i]
        radius = summaries[i]["safety"].get("settings", {}).get("critical_distance_mm", 0.25)
        location = {"limit": limit, "words": words, "point": point, "ratio": ratio, "entry": entry, "radius": radius}
        if do_render:
            png = pathlib.Path(work) / f"worst_{limit}.png"
            ok, message = render(sweep.dir / point, RENDER_FIELDS[limit], entry["critical_distance"]["position_mm"],
                                 radius, png)
            location.update(png=png if ok else None, render_note=message)
        found.append(location)
    return found


# --- the page ----------------------------------------------------------------------------------

CSS = """
body { font-family: sans-serif; margin: 1.5em; color: #222; max-width: 1400px; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: left; vertical-align: top; }
th { background: #f0f0f0; }
td.pass { background: #dff0d8; } td.fail { background: #f2dede; } td.undecided { background: #fcf8e3; }
.note { color: #555; font-size: 0.85em; } td.note { min-width: 18em; } .warning { color: #b00; }
figure { display: inline-block; margin: 0.5em; vertical-align: top; width: 640px; max-width: 100%; }
figure img { width: 100%; border: 1px solid #ddd; } figure.wide { width: 1300px; } figcaption { font-size: 0.85em; max-width: 900px; }
pre { background: #f7f7f7; padding: 0.5em; font-size: 0.8em; overflow-x: auto; }
"""

# Counts the images the browser decoded and says so in the page (the test reads it from the DOM).
CHECK_SCRIPT = """
window.addEventListener("load", function () {
  var images = document.images, decoded = 0;
  for (var k = 0; k < images.length; ++k) {
    var ok = images[k].complete && images[k].naturalWidth > 0;
    images[k].setAttribute("data-decoded", ok ? "yes" : "no");
    decoded += ok ? 1 : 0;
  }
  var marker = document.getElementById("image-check");
  marker.textContent = "images decoded: " + decoded + " of " + images.length;
  marker.setAttribute("data-decoded", decoded);
  marker.setAttribute("data-images", images.length);
});
"""


def e(text):
    return html.escape(str(text))


def design_table(sweep, summaries, bands):
    t = sweep.table
    keys = sweep.swept_keys
    has_bands = bool(bands)
    head = ["#", "point"] + [sweep_figures.key_label(k) for k in keys] + ["status", "verdict"]
    if has_bands:
        head.append("verdict with error band")
    for limit, words in SAFETY_LIMITS:
        head.append(f"{words}: critical-distance value / limit" + (" [error band]" if has_bands else ""))
    head += ["point maxima (mesh-dependent)", "wall [s]", "notes"]
    rows = ["<tr>" + "".join(f"<th>{e(h)}</th>" for h in head) + "</tr>"]
    for i in range(sweep.rows):
        status = t["status"][i]
        overall = verdict_word(t["verdict"][i]) if status == "completed" else ""
        attributes = {"data-point": t["point"][i], "data-status": status, "data-verdict": overall}
        cells = [f"<td>{i + 1}</td>", f"<td>{e(t['point'][i])}</td>"]
        for key in keys:
            value = t[key][i]
            cells.append(f"<td>{e(number(value) if isinstance(value, float) else value)}</td>")
        cells.append(f"<td>{e(status)}</td>")
        cells.append(f'<td class="{overall}">{e(overall)}</td>')
        band_of = bands.get(i, {})
        if has_bands:
            band_verdicts = [band_of[limit]["verdict"] for limit, _ in SAFETY_LIMITS if limit in band_of]
            band_overall = ("fail" if "fail" in band_verdicts else "undecided" if "undecided" in band_verdicts
                            else "pass" if band_verdicts else "")
            attributes["data-band-verdict"] = band_overall
            cells.append(f'<td class="{band_overall}">{e(band_overall or "no band")}</td>')
        summary = summaries.get(i, {})
        for limit, _ in SAFETY_LIMITS:
            verdict = verdict_word(t[f"verdict_{limit}"][i]) if status == "completed" and f"verdict_{limit}" in t else ""
            attributes[f"data-verdict-{limit.replace('_', '-')}"] = verdict
            entry = summary.get("safety", {}).get(limit)
            text = ""
            if status == "completed" and entry:
                text = (f"{number(entry['critical_distance']['value'], UNITS[limit])} / "
                        f"{number(entry['limit'], UNITS[limit])}: {verdict}")
                if limit in band_of:
                    band = band_of[limit]
                    text += f" [{band['low']:.4g}, {band['high']:.4g}]: {band['verdict'] or 'no verdict'}"
            cells.append(f'<td class="{verdict}">{e(text)}</td>')
        maxima = ""
        if status == "completed":
            maxima = "; ".join(f"{words} {number(summary['safety'][limit]['point_max']['value'], UNITS[limit])}"
                               for limit, words in SAFETY_LIMITS if limit in summary.get("safety", {}))
        cells.append(f"<td>{e(maxima)}</td>")
        wall = summary.get("solver", {}).get("wall_s")
        cells.append(f"<td>{e(number(wall))}</td>")
        # The error names the violated rule; the coarse mesh is spelt out once, above the table.
        notes = [t["error"][i] or t["rules"][i], "coarse mesh" if "coarse_mesh" in t and t["coarse_mesh"][i] else ""]
        cells.append(f"<td class='note'>{e('; '.join(n for n in notes if n))}</td>")
        attrs = " ".join(f'{k}="{e(v)}"' for k, v in attributes.items())
        rows.append(f"<tr class='design' {attrs}>" + "".join(cells) + "</tr>")
    return '<table id="designs">' + "\n".join(rows) + "</table>"


def software_section(summaries):
    """The software each run recorded, one row per distinct combination."""
    combos = {}
    unrecorded = []
    for i, s in summaries.items():
        software = s.get("software")
        if software:
            combos.setdefault(tuple((k, str(software.get(k, ""))) for k, _ in SOFTWARE), []).append(i)
        else:
            unrecorded.append(i)
    rows = ["<tr>" + "".join(f"<th>{e(w)}</th>" for _, w in SOFTWARE) + "<th>runs</th></tr>"]
    for combo, runs in combos.items():
        rows.append("<tr class='software'>" + "".join(f"<td>{e(v)}</td>" for _, v in combo) + f"<td>{len(runs)}</td></tr>")
    text = '<table id="software">' + "\n".join(rows) + "</table>" if combos else ""
    if unrecorded:
        text += (f"<p class='note'>{len(unrecorded)} run(s) did not record their software (summary.json before "
                 "needlefem wrote <code>software</code>).</p>")
    if len(combos) > 1:
        text += "<p class='warning'>The runs were made with different software.</p>"
    text += (f"<p class='note'>Report drawn with Python {e(sys.version.split()[0])}, matplotlib "
             f"{e(matplotlib.__version__)}; pictures with ParaView's pvbatch.</p>")
    return text


def settings_section(sweep, summaries):
    with h5py.File(sweep.dir / "sweep.h5", "r") as f:
        sweep_file = str(f.attrs.get("sweep_file", ""))
        base_case = str(f.attrs.get("base_case", ""))
    parts = [f"<p>Sweep file <code>{e(sweep_file)}</code>, base case <code>{e(base_case)}</code>.</p>"]
    grid = ["<tr><th>swept key</th><th>values</th></tr>"]
    for key in sweep.swept_keys:
        values = sorted({v for v in sweep.table[key] if not (isinstance(v, float) and math.isnan(v))},
                        key=lambda v: (isinstance(v, str), v))
        grid.append(f"<tr><td>{e(sweep_figures.key_label(key))} (<code>{e(key)}</code>)</td>"
                    f"<td>{e(', '.join(number(v) if isinstance(v, float) else str(v) for v in values))}</td></tr>")
    parts.append('<table id="grid">' + "".join(grid) + "</table>")
    first = next((s for s in summaries.values() if s.get("status") == "completed"), None)
    if first:
        settings = first.get("safety", {}).get("settings", {})
        if settings:
            parts.append(f"<p>Safety metrics: critical distance {e(settings.get('critical_distance_mm'))} mm, "
                         f"percentile {e(settings.get('percentile'))} over the {e(settings.get('region', ''))}.</p>")
        if "material" in first:
            parts.append(f"<p>Material: {e(first['material'].get('description', first['material'].get('name')))}</p>")
    for title, path in (("sweep file", sweep_file), ("base case", base_case)):
        if path and pathlib.Path(path).is_file():
            parts.append(f"<details open><summary>{e(title)} {e(path)}</summary><pre>"
                         f"{e(pathlib.Path(path).read_text())}</pre></details>")
        elif path:  # the sweep records the path as it was given: relative to where it ran
            parts.append(f"<p class='note'>The {e(title)} {e(path)} is not found from {e(pathlib.Path.cwd())}.</p>")
    if first:
        parts.append("<details><summary>resolved case of the first completed design (every key)</summary><pre>"
                     f"{e(json.dumps(first.get('case', {}), indent=1))}</pre></details>")
    return "\n".join(parts)


def worst_section(locations):
    if not locations:
        return "<p>No completed run reports safety metrics.</p>"
    parts = []
    for loc in locations:
        entry, limit = loc["entry"], loc["limit"]
        cd, pm = entry["critical_distance"], entry["point_max"]
        position = ", ".join(f"{x:.3g}" for x in cd["position_mm"])
        point_position = ", ".join(f"{x:.3g}" for x in pm.get("position_mm", []))
        parts.append(
            f"<div class='worst' data-limit='{e(limit)}' data-point='{e(loc['point'])}'>"
            f"<h3>{e(loc['words'])}: {e(loc['point'])}</h3>"
            f"<p>Critical-distance value {number(cd['value'], UNITS[limit])} = {loc['ratio']:.3g} of the limit "
            f"{number(entry['limit'], UNITS[limit])} ({e(entry.get('verdict', ''))}), ball of radius "
            f"{loc['radius']:g} mm centred at ({position}) mm at t = {cd['time_s']:g} s; point maximum "
            f"{number(pm['value'], UNITS[limit])} at ({point_position}) mm, t = {pm['time_s']:g} s "
            "(reference positions).</p>")
        if loc.get("png"):
            parts.append(f"<figure><img alt='{e(loc['words'])} worst location' src='{data_uri(loc['png'])}'>"
                         f"<figcaption>Running maximum of {e(RENDER_FIELDS[limit])} on the plane y = "
                         f"{cd['position_mm'][1]:.3g} mm through the ball's centre (red circle: the averaging ball), "
                         f"{e(loc['point'])}.</figcaption></figure>")
        elif loc.get("render_note"):
            parts.append(f"<p class='note'>{e(loc['render_note'])}</p>")
        parts.append("</div>")
    return "\n".join(parts)


def page(sweep, summaries, figures, locations, bands, unmatched_bands, bands_path):
    t = sweep.table
    counts = {}
    for status in t["status"]:
        counts[status] = counts.get(status, 0) + 1
    verdicts = [verdict_word(t["verdict"][i]) for i in range(sweep.rows) if t["status"][i] == "completed"]
    warning = sweep.coarse_mesh_warning(list(range(sweep.rows)))
    band_note = ""
    if bands_path:
        band_note = (f"<p>Error bands: <code>{e(bands_path)}</code>, {len(bands)} design(s) of the table matched "
                     "(three refinement levels; band = fine value ± GCI, verdict pass below the limit, fail above, "
                     "undecided when the limit lies inside).")
        if unmatched_bands:
            band_note += f" Not in this sweep: {e(', '.join(unmatched_bands))}."
        band_note += "</p>"
    body = [
        f"<h1>Study report: {e(sweep.dir.resolve().name)}</h1>",
        f"<p>Sweep <code>{e(sweep.dir.resolve())}</code>, {sweep.rows} design points: "
        + ", ".join(f"{n} {e(s)}" for s, n in sorted(counts.items()))
        + f"; of the completed, {verdicts.count('pass')} pass and {verdicts.count('fail')} fail. "
        f"Written {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC.</p>",
        f"<p class='warning'>{e(warning)}</p>" if warning else "",
        '<p id="image-check" class="note">images decoded: not checked (scripts off)</p>',
        "<h2>Designs</h2>",
        "<p class='note'>Verdict: the critical-distance value (the field averaged over a ball, maximised over the "
        "tissue and time) against each limit; the run fails when any limit fails. Point maxima next to a needle "
        "edge change with the mesh and are not judged.</p>",
        band_note,
        design_table(sweep, summaries, bands),
        "<h2>Figures</h2>",
        "".join(f"<figure class='{'wide' if png_width(png) > 1500 else ''}'><img alt='{e(png.stem)}' "
                f"src='{data_uri(png)}'><figcaption>{e(caption)}</figcaption></figure>" for png, caption in figures),
        "<h2>Worst location of each limited metric</h2>",
        worst_section(locations),
        "<h2>Settings</h2>",
        settings_section(sweep, summaries),
        "<h2>Software</h2>",
        software_section(summaries),
    ]
    return ("<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
            f"<title>Study report: {e(sweep.dir.resolve().name)}</title><style>{CSS}</style>"
            f"<script>{CHECK_SCRIPT}</script></head><body>\n" + "\n".join(body) + "\n</body></html>\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sweep_dir")
    parser.add_argument("--out", help="the HTML page (default SWEEP_DIR/report.html)")
    parser.add_argument("--bands", help="study_bands.csv, its folder, or `needlefem converge` folder(s)")
    parser.add_argument("--design-grid", help="grid of the design figures (a [[grid]] name)")
    parser.add_argument("--rate-grid", help="grid of the strain-rate figure")
    parser.add_argument("--no-render", action="store_true", help="leave out the ParaView pictures")
    args = parser.parse_args(argv)
    try:
        sweep, summaries = load_sweep(args.sweep_dir)
        bands, unmatched = {}, []
        if args.bands:
            bands, unmatched = match_bands(sweep, read_bands(args.bands))
        out = pathlib.Path(args.out) if args.out else sweep.dir / "report.html"
        with tempfile.TemporaryDirectory(prefix="study_report_") as work:
            figures = sweep_figures.all_figures(sweep, pathlib.Path(work) / "figures", args.design_grid, args.rate_grid)
            locations = worst_locations(sweep, summaries, work, not args.no_render)
            text = page(sweep, summaries, figures, locations, bands, unmatched, args.bands)
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text, encoding="utf-8")
    except ReportError as error:
        print(f"study_report: {error}", file=sys.stderr)
        return 1
    for loc in locations:
        if loc.get("render_note", "").startswith("not rendered"):
            print(f"study_report: warning: {loc['words']}: {loc['render_note']}", file=sys.stderr)
    print(f"wrote {out} ({sweep.rows} designs, {len(figures) + sum(1 for l in locations if l.get('png'))} images)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
