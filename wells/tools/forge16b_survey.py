#!/usr/bin/env python3
"""Convert the Utah FORGE 16B(78)-32 final survey report (fixed-width text, feet) to a survey CSV
that drillpath reads, and check the CSV against the report, value by value.

Reads  wells/forge-16b/16B78-32_Final_Survey_Report.txt  (the unchanged real file)
Writes wells/forge-16b/16B78-32_survey.csv
       (md [ft],inc [deg],azi [deg] and the report's other eight columns, with units)

Standard library only. Run from anywhere:

    python3 wells/tools/forge16b_survey.py          # writes the CSV, then checks it
    python3 wells/tools/forge16b_survey.py --check  # checks the committed CSV, writes nothing

Every value is copied as the report's text (no rounding, no unit conversion). The check fails
loudly (exit status 1, a message per problem) when:
- the report is not the expected file (size and SHA-256 of the published copy; see SOURCE.md);
- its header is not the expected one (minimum curvature, grid north, the column and unit lines);
- a line after the header is neither blank nor a station of exactly 11 numbers;
- the stations are not the 428 expected, MD 0 to 10,947 ft, strictly increasing;
- the CSV, read back, differs from the report in any station or any value (as text and as number);
- minimum curvature from (MD, INC, AZI) does not reproduce the report's TVD, N/S and E/W within
  0.01 ft and its DLS within 0.05 deg/100 ft (a check that the columns were taken in order).
"""
import csv
import hashlib
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WELL = os.path.join(os.path.dirname(HERE), "forge-16b")
REPORT = os.path.join(WELL, "16B78-32_Final_Survey_Report.txt")
CSV_OUT = os.path.join(WELL, "16B78-32_survey.csv")
SCRIPT = "wells/tools/forge16b_survey.py"

REPORT_BYTES = 54311
EXPECTED_SHA256 = "3fef24321a7c20918e67952e262505fbf72165425cd33645ca2fd422c2471254"
N_STATIONS = 428
FIRST_MD, LAST_MD = "0.00", "10947.00"

# The report's columns, in order, and the CSV header names (unit in brackets). The first three
# are the ones drillpath reads; the others are carried along for reference.
COLUMNS = ["MD", "INC", "AZI", "TVD", "SSTVD", "N/S", "NORTHING", "E/W", "EASTING", "VSEC", "DLS"]
UNITS = ["(ft)", "(deg)", "(deg)", "(ft)", "(ft)", "(ft)", "(Ft)", "(ft)", "(Ft)", "(ft)", "(deg/100ft)"]
CSV_HEADER = ["md [ft]", "inc [deg]", "azi [deg]", "tvd [ft]", "sstvd [ft]", "north [ft]",
              "northing [US ft]", "east [ft]", "easting [US ft]", "vsec [ft]", "dls [deg/100ft]"]

# Header facts that must be present (key, value), as written in the report.
HEADER_FACTS = [
    ("WELL", "16B(78)-32"),
    ("CALCULATION METHOD", "Minimum Curvature"),
    ("NORTH REF", "Grid"),
    ("VSECT DIREC", "106.85deg"),
    ("KB ELEV", "5447.65ft"),
    ("DATE", "6/26/2023"),
]

COMMENTS = [
    "drillpath example forge-16b: REAL well Utah FORGE 16B(78)-32, final directional survey (DERIVED FILE, do not edit)",
    "derived by %s from 16B78-32_Final_Survey_Report.txt (unchanged, in this folder): every value copied as the report's text, no rounding, no conversion" % SCRIPT,
    "depths in feet from KB (KB elevation 5447.65 ft); azimuth GRID north (UTM zone 12N, NAD83 Utah-HARN); the report's calculation method: minimum curvature",
    "north/east = the report's N/S and E/W offsets from the wellhead; northing/easting in US survey feet; vsec along 106.85 deg; dls in deg/100 ft",
    "Utah FORGE / University of Utah, Geothermal Data Repository submission 1516, US Department of Energy (CC BY 4.0 as stated in SOURCE.md)",
]

problems = []


def fail(msg):
    problems.append(msg)


def read_report():
    """(header lines, [(line number, [11 tokens])]) of the report; problems recorded."""
    with open(REPORT, "rb") as f:
        raw = f.read()
    if len(raw) != REPORT_BYTES:
        fail("%s: %d bytes, expected %d (is it the unchanged copy?)" % (REPORT, len(raw), REPORT_BYTES))
    sha = hashlib.sha256(raw).hexdigest()
    if sha != EXPECTED_SHA256:
        fail("%s: SHA-256 %s, expected %s (is it the unchanged copy?)" % (REPORT, sha, EXPECTED_SHA256))
    text = raw.decode("ascii")
    if "\n" in text.replace("\r\n", ""):
        fail("%s: expected CRLF line ends throughout" % REPORT)
    lines = text.split("\r\n")
    # header: everything up to and including the units line
    try:
        cols_at = next(i for i, l in enumerate(lines) if l.split()[:1] == ["MD"])
    except StopIteration:
        fail("%s: no column-name line starting with MD" % REPORT)
        return [], []
    if lines[cols_at].split() != COLUMNS:
        fail("%s line %d: columns %s, expected %s" % (REPORT, cols_at + 1, lines[cols_at].split(), COLUMNS))
    if lines[cols_at + 1].split() != UNITS:
        fail("%s line %d: units %s, expected %s" % (REPORT, cols_at + 2, lines[cols_at + 1].split(), UNITS))
    header = lines[:cols_at + 2]
    facts = {}
    for l in header:
        if ":" in l:
            k, v = l.split(":", 1)
            facts[" ".join(k.split())] = v.strip()
    for k, v in HEADER_FACTS:
        if facts.get(k) != v:
            fail("%s: header %s is %r, expected %r" % (REPORT, k, facts.get(k), v))
    stations = []
    for i in range(cols_at + 2, len(lines)):
        tok = lines[i].split()
        if not tok:
            continue
        if len(tok) != 11:
            fail("%s line %d: %d fields, expected 11: %r" % (REPORT, i + 1, len(tok), lines[i]))
            continue
        try:
            [float(t) for t in tok]
        except ValueError:
            fail("%s line %d: not all numbers: %r" % (REPORT, i + 1, lines[i]))
            continue
        stations.append((i + 1, tok))
    if len(stations) != N_STATIONS:
        fail("%s: %d stations, expected %d" % (REPORT, len(stations), N_STATIONS))
    if stations and (stations[0][1][0], stations[-1][1][0]) != (FIRST_MD, LAST_MD):
        fail("%s: MD %s to %s, expected %s to %s" % (REPORT, stations[0][1][0], stations[-1][1][0], FIRST_MD, LAST_MD))
    for (la, a), (lb, b) in zip(stations, stations[1:]):
        if not float(b[0]) > float(a[0]):
            fail("%s line %d: MD %s does not increase (previous %s, line %d)" % (REPORT, lb, b[0], a[0], la))
    return header, stations


def write_csv(stations):
    with open(CSV_OUT, "w", newline="") as f:
        for c in COMMENTS:
            f.write("# " + c + "\n")
        f.write(",".join(CSV_HEADER) + "\n")
        for _, tok in stations:
            f.write(",".join(tok) + "\n")


def check_csv(stations):
    """Read the CSV back and compare it with the report's stations, every value."""
    if not os.path.exists(CSV_OUT):
        fail("%s: missing (run %s without --check)" % (CSV_OUT, SCRIPT))
        return
    with open(CSV_OUT, newline="") as f:
        text = f.read()
    rows = [r for r in csv.reader(l for l in text.splitlines() if l.strip() and not l.lstrip().startswith("#"))]
    if not rows or rows[0] != CSV_HEADER:
        fail("%s: header %s, expected %s" % (CSV_OUT, rows[0] if rows else None, CSV_HEADER))
        return
    data = rows[1:]
    if len(data) != len(stations):
        fail("%s: %d stations, the report has %d" % (CSV_OUT, len(data), len(stations)))
    for k, ((line, tok), row) in enumerate(zip(stations, data)):
        if len(row) != len(tok):
            fail("%s station %d (report line %d): %d values, expected %d" % (CSV_OUT, k + 1, line, len(row), len(tok)))
            continue
        for name, a, b in zip(CSV_HEADER, tok, row):
            if a != b or float(a) != float(b):
                fail("%s station %d (report line %d), %s: CSV %r, report %r" % (CSV_OUT, k + 1, line, name, b, a))


def check_min_curvature(stations):
    """Minimum curvature from (MD, INC, AZI) against the report's TVD, N/S, E/W and DLS."""
    v = [[float(t) for t in tok] for _, tok in stations]
    tvd, n, e = v[0][3], v[0][5], v[0][7]
    worst_pos = worst_dls = 0.0
    for (line, _), a, b in zip(stations[1:], v, v[1:]):
        i1, a1, i2, a2 = map(math.radians, (a[1], a[2], b[1], b[2]))
        c = math.cos(i2 - i1) - math.sin(i1) * math.sin(i2) * (1 - math.cos(a2 - a1))
        dl = math.acos(max(-1.0, min(1.0, c)))
        rf = 1.0 if dl < 1e-12 else 2 / dl * math.tan(dl / 2)
        d = b[0] - a[0]
        n += d / 2 * (math.sin(i1) * math.cos(a1) + math.sin(i2) * math.cos(a2)) * rf
        e += d / 2 * (math.sin(i1) * math.sin(a1) + math.sin(i2) * math.sin(a2)) * rf
        tvd += d / 2 * (math.cos(i1) + math.cos(i2)) * rf
        dls = math.degrees(dl) / d * 100.0
        dpos = max(abs(tvd - b[3]), abs(n - b[5]), abs(e - b[7]))
        worst_pos, worst_dls = max(worst_pos, dpos), max(worst_dls, abs(dls - b[10]))
        if dpos > 0.01:
            fail("%s line %d: minimum curvature gives TVD %.3f N %.3f E %.3f ft, the report %.2f %.2f %.2f"
                 % (REPORT, line, tvd, n, e, b[3], b[5], b[7]))
        if abs(dls - b[10]) > 0.05:
            fail("%s line %d: minimum curvature gives DLS %.3f deg/100 ft, the report %.2f" % (REPORT, line, dls, b[10]))
    return worst_pos, worst_dls


def main():
    check_only = "--check" in sys.argv[1:]
    _, stations = read_report()
    if problems:  # never write a CSV from a report that is not the expected one
        for p in problems:
            print("ERROR: " + p, file=sys.stderr)
        sys.exit(1)
    if not check_only:
        write_csv(stations)
    check_csv(stations)
    worst_pos, worst_dls = check_min_curvature(stations)
    if problems:
        for p in problems:
            print("ERROR: " + p, file=sys.stderr)
        print("FAILED: %d problem(s)" % len(problems), file=sys.stderr)
        sys.exit(1)
    print("%s %s: %d stations, MD %s-%s ft, every value equal to the report's; minimum curvature "
          "reproduces TVD/N/E within %.4f ft and DLS within %.3f deg/100 ft"
          % ("checked" if check_only else "wrote and checked", os.path.relpath(CSV_OUT, os.path.dirname(os.path.dirname(WELL))),
             len(stations), stations[0][1][0], stations[-1][1][0], worst_pos, worst_dls))


if __name__ == "__main__":
    main()
