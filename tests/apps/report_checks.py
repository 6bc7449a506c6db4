"""Checks of a campaign's report.html files as an engineer opens them (docs/report.md "Figures"),
shared by the app tests that run a campaign: each report is loaded by Debian's headless Chromium,
which must log no console message (an SVG attribute Chromium cannot parse, such as a coordinate
"nan", is logged as a console error), and its DOM after load must hold every figure of the file.
The file is then read with Python's xml.etree (not our code): every figure is an <svg> whose axis
labels name a unit in parentheses, and each run has the figures of its kind, counted by the
data-figure attribute the report gives each <svg>:
- every calibration and acceptance report: at least one time series ("time-series");
- an IMU acceptance report: at least three acceptance figures (acceleration and body-rate error
  per orientation, "acceptance-accel" / "acceptance-rate", and the thermal acceptance's
  "acceptance-thermal" when the sequence logs a thermal profile);
- an ADS calibration report: the raw data ("ads-raw") and the fitted surface's residual map
  ("ads-surface-residual").
"""
import json
import pathlib
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from app_checks import expect  # noqa: E402

CHROMIUM_TIMEOUT_S = 120
UNIT_IN_PARENTHESES = re.compile(r"\([^()]+\)")


def local(tag):
    return tag.split("}")[-1]


def chromium_dom(report, profile_dir):
    """Chromium's DOM of the page after load, and the console messages it logged."""
    result = subprocess.run(
        ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         f"--user-data-dir={profile_dir}", "--enable-logging=stderr", "--v=0", "--dump-dom",
         report.resolve().as_uri()],
        capture_output=True, text=True, timeout=CHROMIUM_TIMEOUT_S)
    console = [line for line in result.stderr.splitlines() if ":CONSOLE" in line]
    return result.stdout, console


def figures_of(report):
    """Each <svg> of the file: its data-figure kind and its x and y axis labels."""
    root = ET.parse(report).getroot()
    figures = []
    for svg in root.iter():
        if local(svg.tag) != "svg":
            continue
        labels = {}
        for text in svg.iter():
            if local(text.tag) == "text" and text.get("class") in ("xlabel", "ylabel"):
                labels[text.get("class")] = "".join(text.itertext())
        figures.append((svg.get("data-figure", ""), labels.get("xlabel"), labels.get("ylabel")))
    return figures


def run_kind(run_dir):
    """("imu" or "ads", True for an acceptance run, True when the sequence logs a thermal
    profile) from the run's meta.json."""
    meta = json.loads((run_dir / "meta.json").read_text())
    kind = meta["sequence"]["unit_kind"]
    acceptance = any(u.get("mode", 0) != 0 for u in meta["units"] if u.get("kind") == kind)
    thermal = any(s["kind"] == "thermal_profile" for s in meta["sequence"]["steps"])
    return kind, acceptance, thermal


def check_report(report, profile_dir):
    """One report.html by the rules in the module's description; returns its figure kinds."""
    figures = figures_of(report)
    dom, console = chromium_dom(report, profile_dir)
    expect(not console, f"{report}: Chromium logged console messages", console[:5])
    expect(dom.count("<svg") == len(figures) > 0,
           f"{report}: Chromium's DOM holds {dom.count('<svg')} svg, the file {len(figures)}")
    for kind, xlabel, ylabel in figures:
        for axis, label in (("x", xlabel), ("y", ylabel)):
            expect(label and UNIT_IN_PARENTHESES.search(label),
                   f"{report}: a {kind or 'unnamed'} figure's {axis} axis label names no unit",
                   label)
    kinds = [k for k, _, _ in figures]
    unit_kind, acceptance, thermal = run_kind(report.parent)
    expect("time-series" in kinds, f"{report}: no time-series figure", kinds)
    if unit_kind == "imu" and acceptance:
        judged = [k for k in kinds if k.startswith("acceptance-")]
        expect(len(judged) >= 3, f"{report}: fewer than three acceptance figures", kinds)
        expect("acceptance-accel" in judged and "acceptance-rate" in judged,
               f"{report}: no acceleration or body-rate acceptance figure", kinds)
        expect("acceptance-thermal" in judged or not thermal,
               f"{report}: the sequence logs a thermal profile, the report has no thermal "
               "acceptance figure", kinds)
    if unit_kind == "ads" and not acceptance:
        expect("ads-raw" in kinds and "ads-surface-residual" in kinds,
               f"{report}: no raw-data or surface-residual figure", kinds)
    return kinds


def check_reports(run_dirs, profile_dir):
    """Every run's report.html; returns {run name: figure kinds}."""
    found = {}
    for run_dir in run_dirs:
        found[run_dir.name] = check_report(run_dir / "report.html", profile_dir)
        print(f"{run_dir.name}/report.html: {len(found[run_dir.name])} figures, "
              f"kinds {sorted(set(found[run_dir.name]))}")
    return found
