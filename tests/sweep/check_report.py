#!/usr/bin/python3
"""Test of postprocess/study_report.py on the brain-tip sweep of tests/sweep/tiny_tip.toml (made by
the sweep.safety_beside_steering test), read back through headless Chromium.

  - bad input: a folder that is not a sweep, and a sweep whose completed point lost its
    summary.json, each stop with one line naming the path and a non-zero exit;
  - the report of the sweep with made-up three-level error bands (a study_bands.csv as
    tests/benchmarks/bench_study.py --levels 3 writes it) is one HTML file with nothing loaded from
    elsewhere (every image a data URI that decodes as a non-blank PNG);
  - `chromium --headless --dump-dom`: the page's script counted every image decoded
    (naturalWidth > 0); the table has one row per design of sweep.csv with its status, verdict
    and per-limit verdicts, and the band verdicts of study_bands.csv; each limit's worst location
    is the design with the largest critical-distance value over its limit, with a picture; the
    settings (sweep file, base case, grid) and the software versions the runs recorded appear;
  - `chromium --headless --screenshot`: a non-blank PNG of the page (report.png in the test folder).
"""
import argparse
import base64
import csv
import html.parser
import io
import json
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from check_sweep import LIMITS, check, failures  # noqa: E402


def png_ok(data):
    """PNG bytes that decode to an image that is not one flat colour."""
    import matplotlib.image
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        return False
    image = matplotlib.image.imread(io.BytesIO(data), format="png")
    return image.shape[0] > 50 and image.shape[1] > 50 and float(np.std(image[..., :3])) > 0.01


class Dom(html.parser.HTMLParser):
    """The parts of the dumped DOM the test reads: design rows, images, worst-location blocks, text."""

    def __init__(self):
        super().__init__()
        self.rows, self.images, self.worst, self.text = [], [], [], []
        self.marker = {}
        self.software_cells, self._in_software, self._in_cell = [], False, False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "tr" and a.get("class") == "design":
            self.rows.append(a)
        elif tag == "img":
            self.images.append(a)
        elif tag == "div" and a.get("class") == "worst":
            self.worst.append(dict(a, images=0))
        elif tag == "p" and a.get("id") == "image-check":
            self.marker = a
        elif tag == "table" and a.get("id") == "software":
            self._in_software = True
        elif tag == "td" and self._in_software:
            self._in_cell = True
            self.software_cells.append("")
        if tag == "img" and self.worst:
            self.worst[-1]["images"] += 1

    def handle_endtag(self, tag):
        if tag == "table":
            self._in_software = False
        if tag == "td":
            self._in_cell = False

    def handle_data(self, data):
        self.text.append(data)
        if self._in_cell:
            self.software_cells[-1] += data


def chromium(args, url, *options):
    with tempfile.TemporaryDirectory(prefix="chromium_profile_") as profile:
        return subprocess.run([args.chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                               f"--user-data-dir={profile}", *options, url], capture_output=True, text=True, timeout=120)


def bad_input(args, sweep_dir, out):
    not_sweep = out / "not_a_sweep"
    not_sweep.mkdir(parents=True)
    result = subprocess.run([sys.executable, args.report, str(not_sweep)], capture_output=True, text=True)
    lines = result.stderr.strip().splitlines()
    check(result.returncode != 0 and len(lines) == 1 and str(not_sweep) in lines[0] and "not a sweep directory" in lines[0],
          f"not a sweep: exit {result.returncode}, one line naming the folder: {lines}")
    broken = out / "missing_run"
    broken.mkdir()
    for name in ("sweep.h5", "sweep.csv"):
        shutil.copy(sweep_dir / name, broken / name)
    rows = list(csv.DictReader(open(sweep_dir / "sweep.csv")))
    kept, lost = rows[0]["point"], rows[1]["point"]
    (broken / kept).mkdir()
    for name in ("summary.json", "history.csv"):
        shutil.copy(sweep_dir / kept / name, broken / kept / name)
    result = subprocess.run([sys.executable, args.report, str(broken)], capture_output=True, text=True)
    lines = result.stderr.strip().splitlines()
    check(result.returncode != 0 and len(lines) == 1 and str(broken / lost / "summary.json") in lines[0]
          and "missing" in lines[0], f"a completed point without its run: exit {result.returncode}, one line: {lines}")


def swept_keys(sweep_dir):
    with open(sweep_dir / "sweep.csv") as f:
        columns = next(csv.reader(f))
    return columns[columns.index("grids") + 1:columns.index("status")]


def write_bands(sweep_dir, rows, path):
    """A study_bands.csv for the sweep's designs (bench_study.py's columns), each limit's band around the
    design's own critical-distance value, 5 % either side; the first design's strain-rate band is
    marked undecided. Returns point -> limit -> band verdict."""
    keys = swept_keys(sweep_dir)
    expected = {}
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["design", "grid", *keys, "metric", "values", "behaviour", "observed_order", "gci_fine",
                         "verdict"])
        for n, row in enumerate(rows):
            summary = json.loads((sweep_dir / row["point"] / "summary.json").read_text())
            expected[row["point"]] = {}
            design = [f"design{n}", "main", *(row[k] for k in keys)]
            for limit in LIMITS:
                value = summary["safety"][limit]["critical_distance"]["value"]
                verdict = "undecided" if (n == 0 and limit == "strain_rate_per_s") else "pass"
                expected[row["point"]][limit] = verdict
                writer.writerow([*design, f"safety.{limit}.critical_distance",
                                 f"{value * 1.02:.6g} / {value * 0.99:.6g} / {value:.6g}", "monotone", "1.7", "0.05",
                                 verdict])
            writer.writerow([*design, "needle.max_axial_force_n", "1 / 1 / 1", "monotone", "2", "0.01", ""])
    return expected


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--sweep-dir", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--report", required=True, help="postprocess/study_report.py")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    args = parser.parse_args()
    sweep_dir, out = pathlib.Path(args.sweep_dir), pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    if not shutil.which(args.chromium):
        print(f"{args.chromium}: not found (scripts/setup.sh --tests installs Debian's chromium)")
        return 1

    bad_input(args, sweep_dir, out)
    rows = list(csv.DictReader(open(sweep_dir / "sweep.csv")))
    summaries = {r["point"]: json.loads((sweep_dir / r["point"] / "summary.json").read_text()) for r in rows}
    band_verdicts = write_bands(sweep_dir, rows, out / "study_bands.csv")

    page = out / "report.html"
    start = time.monotonic()
    result = subprocess.run([sys.executable, args.report, str(sweep_dir), "--out", str(page), "--bands",
                             str(out / "study_bands.csv")], capture_output=True, text=True)
    print(result.stdout[-1500:], result.stderr[-1500:])
    check(result.returncode == 0 and page.exists(), f"study_report.py exits 0 in {time.monotonic() - start:.1f} s")
    if not page.exists():
        return 1
    text = page.read_text()
    sources = re.findall(r'src=["\']([^"\']*)', text)
    check(sources and all(s.startswith("data:image/png;base64,") for s in sources),
          f"self-contained: every one of {len(sources)} image sources is a PNG data URI")
    check(not re.search(r"<link|<script[^>]*src=|@import|url\(|https?://", text),
          "no stylesheet, script, font or address loaded from elsewhere")
    decoded = [png_ok(base64.b64decode(s.split(",", 1)[1])) for s in sources]
    check(all(decoded), f"every data URI decodes as a non-blank PNG ({sum(decoded)} of {len(decoded)})")

    dom_run = chromium(args, page.resolve().as_uri(), "--virtual-time-budget=5000", "--dump-dom")
    check(dom_run.returncode == 0 and "</html>" in dom_run.stdout, f"chromium --dump-dom exits {dom_run.returncode}")
    (out / "dom.html").write_text(dom_run.stdout)
    dom = Dom()
    dom.feed(dom_run.stdout)
    images = len(dom.images)
    check(dom.marker.get("data-images") == str(images) and dom.marker.get("data-decoded") == str(images)
          and images == len(sources), f"Chromium decoded every image: marker {dom.marker.get('data-decoded')} of "
                                      f"{dom.marker.get('data-images')}, {images} <img> in the DOM")
    check(all(a.get("data-decoded") == "yes" for a in dom.images), "each <img> marked decoded (naturalWidth > 0)")
    check(images >= 6 + len(LIMITS), f"{images} images: the six sweep figures and a picture per limit")

    word = {"1": "pass", "0": "fail"}
    check([r.get("data-point") for r in dom.rows] == [r["point"] for r in rows],
          f"one table row per design, in sweep.csv's order ({len(dom.rows)} rows)")
    for shown, row in zip(dom.rows, rows):
        point = row["point"]
        check(shown.get("data-status") == row["status"] and shown.get("data-verdict") == word.get(row["verdict"], ""),
              f"{point}: status {shown.get('data-status')}, verdict {shown.get('data-verdict')} as sweep.csv "
              f"({row['status']}, {row['verdict']})")
        for limit in LIMITS:
            attribute = f"data-verdict-{limit.replace('_', '-')}"
            check(shown.get(attribute) == word[row[f"verdict_{limit}"]] == summaries[point]["safety"][limit]["verdict"],
                  f"{point}: {limit} verdict {shown.get(attribute)} = sweep.csv's = summary.json's")
        expected_band = "undecided" if "undecided" in band_verdicts[point].values() else "pass"
        check(shown.get("data-band-verdict") == expected_band,
              f"{point}: verdict with error band {shown.get('data-band-verdict')} (expected {expected_band})")
    page_text = " ".join(" ".join(dom.text).split())
    fine = float(f"{summaries[rows[0]['point']]['safety']['log_strain']['critical_distance']['value']:.6g}")
    band_text = f"[{fine - 0.05 * fine:.4g}, {fine + 0.05 * fine:.4g}]: pass"
    check(band_text in page_text, f"the first design's log-strain band starts at {band_text}")

    check([w.get("data-limit") for w in dom.worst] == list(LIMITS), f"a worst location per limit: "
                                                                     f"{[w.get('data-limit') for w in dom.worst]}")
    ratio = {limit: {p: s["safety"][limit]["critical_distance"]["value"] / s["safety"][limit]["limit"]
                     for p, s in summaries.items()} for limit in LIMITS}
    for block in dom.worst:
        limit, point = block.get("data-limit"), block.get("data-point")
        if limit not in LIMITS or point not in summaries:
            continue
        largest = max(ratio[limit].values())
        check(ratio[limit][point] >= largest * (1 - 1e-12) and block["images"] == 1,
              f"{limit}: worst location {point} (value/limit {ratio[limit][point]:.6g}, the largest {largest:.6g}) "
              f"with {block['images']} picture")

    import h5py
    with h5py.File(sweep_dir / "sweep.h5", "r") as f:
        sweep_file, base_case = str(f.attrs["sweep_file"]), str(f.attrs["base_case"])
    check(sweep_file in page_text and base_case in page_text, "the sweep file and the base case are named")
    sweep_text = " ".join(pathlib.Path(sweep_file).read_text().split())
    grid = [", ".join(sorted({r[k] for r in rows}, key=float)) for k in swept_keys(sweep_dir)]
    check(sweep_text in page_text and all(values in page_text for values in grid),
          f"the settings: the sweep file's text and the swept values ({grid})")
    software = summaries[rows[0]["point"]].get("software", {})
    check(set(software) >= {"needlefem", "commit", "petsc", "sundials", "gmsh_api", "hdf5"},
          f"summary.json records the software: {software}")
    check(software.get("petsc", "").startswith("3.") and software.get("hdf5", "").startswith("1.")
          and software.get("commit") not in (None, "", "unknown"), f"versions and commit are filled in: {software}")
    check(all(str(v) in dom.software_cells for v in software.values()) and str(len(rows)) in dom.software_cells,
          f"the software table shows what the runs recorded: {dom.software_cells}")

    shot = out / "report.png"
    shot_run = chromium(args, page.resolve().as_uri(), "--window-size=1400,5600", f"--screenshot={shot}")
    check(shot_run.returncode == 0 and shot.exists() and png_ok(shot.read_bytes()),
          f"chromium --screenshot: {shot} written and not blank")
    print(f"{len(failures)} check(s) failed" if failures else "every check passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
