#!/usr/bin/env python3
"""Figures that cannot mislead: a lint of gnuplot's SVG pictures.

usage: figure_lint.py PAGE.html | FIGURE.svg ...
       figure_lint.py --self-test   (gnuplot draws the cases each rule must find)

A report page is read as the browser left it (its figures are embedded as
base64 SVG, each with its caption); SVG files are read as they are, with
no caption.  For each figure it requires:

- the key (gnuplot's opaque box, demvv draws every key so) lies inside the
  picture: a key wider than the picture is cut at its edge;
- the key hides no data: no segment of a curve, error bar or band crosses
  the box, and no marker touches it (the box is opaque, so what lies under
  it is not seen), and it covers no label of the axes or the title;
- a caption names only what the figure draws: "dashed" needs a dashed
  curve, "solid" a solid one, "bars" error bars, "square" square markers,
  "circle" circles or circular markers.

The geometry is gnuplot's own (its SVG gives every coordinate in the
picture's pixels); a curve is what a plot group (gnuplot_plot_N) draws
before the key box, the key's samples are what the same groups draw after
it.  Exit 1 with one line per finding, else 0.
"""
import base64
import html
import re
import sys
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"
XLINK = "{http://www.w3.org/1999/xlink}href"
# A key box is drawn with its edge on the frame's when it is placed inside
# (top left ...): 1.5 px of the box's rim is not a part of it a curve can
# hide behind.
RIM = 1.5


def numbers(text):
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", text)]


def path_segments(d):
    """Segments of an SVG path of absolute M, L and Z commands (all gnuplot writes)."""
    segments, start, here = [], None, None
    for command, args in re.findall(r"([MLZz])([^MLZz]*)", d):
        if command in "Zz":
            if here and start:
                segments.append((here, start))
            here = start
            continue
        values = numbers(args)
        points = list(zip(values[0::2], values[1::2]))
        if not points:
            continue
        if command == "M":
            start = here = points[0]
            points = points[1:]
        for p in points:
            segments.append((here, p))
            here = p
    return segments


def crosses(segment, box):
    """Whether a segment enters the open rectangle box = (x0, y0, x1, y1) (Liang-Barsky)."""
    (xa, ya), (xb, yb) = segment
    x0, y0, x1, y1 = box
    dx, dy = xb - xa, yb - ya
    low, high = 0.0, 1.0
    for p, q in ((-dx, xa - x0), (dx, x1 - xa), (-dy, ya - y0), (dy, y1 - ya)):
        if p == 0:
            if q <= 0:
                return False
        else:
            t = q / p
            if p < 0:
                low = max(low, t)
            else:
                high = min(high, t)
    return low < high


def translate_scale(transform):
    m = re.search(r"translate\(([^,]+),([^)]+)\)", transform or "")
    s = re.search(r"scale\(([^)]+)\)", transform or "")
    if not m:
        return None
    return float(m.group(1)), float(m.group(2)), float(s.group(1)) if s else 1.0


class Picture:
    """The parts of one gnuplot SVG the rules read."""

    def __init__(self, text):
        root = ET.fromstring(text)
        self.width = float(re.sub(r"[^\d.]", "", root.get("width", "0")) or 0)
        self.height = float(re.sub(r"[^\d.]", "", root.get("height", "0")) or 0)
        self.keys, self.segments, self.markers, self.labels = [], [], [], []
        self.dashed = self.solid = self.bars = self.squares = self.circles = False
        self._walk(root, in_plot=False, after_key=[False])

    def _walk(self, node, in_plot, after_key):
        for child in node:
            tag = child.tag.replace(SVG, "")
            if tag == "polygon" and child.get("fill", "").upper() in ("#FFFFFF", "WHITE"):
                xy = numbers(child.get("points", ""))
                xs, ys = xy[0::2], xy[1::2]
                self.keys.append((min(xs), min(ys), max(xs), max(ys)))
                after_key[0] = True
                continue
            plot = in_plot or (tag == "g" and (child.get("id") or "").startswith("gnuplot_plot_"))
            if plot and not after_key[0]:
                self._data(child, tag)
            if not plot and tag == "g":
                self._label(child)
            self._walk(child, plot, after_key)

    def _label(self, group):
        """An axis's label, a tick's or the title: a box from its anchor, 6 px a character (narrower than
        any Sans at 12 px, so that a box found overlapping surely does) and its ascent and descent."""
        where = translate_scale(group.get("transform"))
        text = "".join(t.text or "" for t in group.iter(SVG + "text")) + "".join(
            t.text or "" for t in group.iter(SVG + "tspan"))
        if not where or not text.strip() or "rotate" in (group.get("transform") or ""):
            return
        x, y, _ = where
        size = float(group.get("font-size", "12"))
        width = 6 * size / 12 * len(text.strip())
        anchor = group.get("text-anchor", "start")
        left = x - width if anchor == "end" else x - width / 2 if anchor == "middle" else x
        self.labels.append((text.strip(), (left, y - 0.75 * size, left + width, y + 0.2 * size)))

    def _data(self, element, tag):
        if tag == "path":
            segments = path_segments(element.get("d", ""))
            self.segments += segments
            if element.get("stroke-dasharray"):
                self.dashed = True
            else:
                self.solid = self.solid or len(segments) > 0
            self.bars = self.bars or has_error_bars(segments)
        elif tag == "use":
            where = translate_scale(element.get("transform"))
            if where:
                self.markers.append(where)
                shape = element.get(XLINK, "")
                self.squares = self.squares or shape in ("#gpPt3", "#gpPt4", "#gpPt11", "#gpPt12")
                self.circles = self.circles or shape in ("#gpPt5", "#gpPt6")
        elif tag == "circle":
            x, y, r = (float(element.get(k, 0)) for k in ("cx", "cy", "r"))
            self.markers.append((x, y, r))
            self.circles = True


def has_error_bars(segments):
    """A vertical segment with a short horizontal cap centred on one of its ends."""
    ends = set()
    for (xa, ya), (xb, yb) in segments:
        if abs(xa - xb) < 0.01 and abs(ya - yb) > 0.01:
            ends.add((round(xa, 1), round(ya, 1)))
            ends.add((round(xa, 1), round(yb, 1)))
    for (xa, ya), (xb, yb) in segments:
        if abs(ya - yb) < 0.01 and 0 < abs(xb - xa) <= 20:
            if (round((xa + xb) / 2, 1), round(ya, 1)) in ends:
                return True
    return False


CAPTION_WORDS = (
    (r"\bdashed\b", "dashed", "a dashed curve"),
    (r"\bsolid\b", "solid", "a solid curve"),
    (r"\bbars?\b", "bars", "error bars"),
    (r"\bsquares?\b", "squares", "square markers"),
    (r"\bcircles?\b", "circles", "circles or circular markers"),
)


def findings(name, text, caption):
    try:
        p = Picture(text)
    except ET.ParseError as e:
        return ["%s: not an SVG picture (%s)" % (name, e)]
    found = []
    for x0, y0, x1, y1 in p.keys:
        if x0 < -0.5 or y0 < -0.5 or x1 > p.width + 0.5 or y1 > p.height + 0.5:
            found.append("%s: the key (%.0f..%.0f x %.0f..%.0f px) runs past the %gx%g picture"
                         % (name, x0, x1, y0, y1, p.width, p.height))
        inner = (x0 + RIM, y0 + RIM, x1 - RIM, y1 - RIM)
        hidden = sum(1 for s in p.segments if crosses(s, inner))
        touched = sum(1 for x, y, r in p.markers
                      if x + r > inner[0] and x - r < inner[2] and y + r > inner[1] and y - r < inner[3])
        if hidden or touched:
            found.append("%s: the key hides data (%d segments, %d markers under its box)" % (name, hidden, touched))
        for text, (a, b, c, d) in p.labels:
            if a < inner[2] and c > inner[0] and b < inner[3] and d > inner[1]:
                found.append("%s: the key covers the label '%s'" % (name, text))
    for pattern, attribute, what in CAPTION_WORDS:
        if caption and re.search(pattern, caption, re.I) and not getattr(p, attribute):
            found.append("%s: the caption names %s, which the figure does not draw (caption: %s)"
                         % (name, what, caption[:120]))
    return found


def page_figures(page):
    for figure in re.findall(r"<figure>(.*?)</figure>", page, re.S):
        img = re.search(r'<img[^>]*alt="([^"]*)"[^>]*src="data:image/svg\+xml;base64,([^"]+)"', figure)
        caption = re.search(r"<figcaption>(.*?)</figcaption>", figure, re.S)
        if img:
            yield (html.unescape(img.group(1)), base64.b64decode(img.group(2)).decode("utf-8"),
                   html.unescape(re.sub(r"<[^>]+>", "", caption.group(1))) if caption else "")


def self_test():
    """The rules fail where they should: gnuplot draws a key over a line, a key wider than its picture, a key
    below the frame that must pass, and a caption names a dashed line that is not drawn."""
    import subprocess
    import tempfile
    plot = "set terminal svg size 400,300 font 'Sans,12' background rgb 'white'\nset key %s\n" \
           "plot [0:1] x title 'a line', 1-x title '%s'\n"
    cases = [("top left box opaque", "b", "", "hides data"),
             ("below box opaque", "b" * 120, "", "runs past"),
             ("below box opaque\nset bmargin 6", "b", "the dashed line is b", "the caption names a dashed"),
             ("below box opaque\nset bmargin 6", "b", "two solid lines", None)]
    with tempfile.TemporaryDirectory() as work:
        for key, title, caption, expected in cases:
            svg = subprocess.run(["gnuplot"], input=plot % (key, title), capture_output=True, text=True,
                                 cwd=work, check=True).stdout
            got = findings("self-test", svg, caption)
            if expected is None and got or expected and not any(expected in g for g in got):
                print("FAIL: the lint's self-test with key '%s': expected %s, found %s" % (key, expected, got))
                return 1
    print("figure lint self-test: a key over a line, a key past the picture and a caption naming a dashed line "
          "that is not drawn are found; a key below the frame passes")
    return 0


def main(paths):
    if paths == ["--self-test"]:
        return self_test()
    found, count = [], 0
    for path in paths:
        text = open(path, encoding="utf-8").read()
        if path.endswith(".svg"):
            figures = [(path, text, "")]
        else:
            figures = list(page_figures(text))
        for name, svg, caption in figures:
            count += 1
            found += findings(name, svg, caption)
    for line in found:
        print("FAIL: " + line)
    if count == 0:
        print("FAIL: no figure found in " + ", ".join(paths))
        return 1
    if not found:
        print("figure lint: %d figures, keys inside their pictures and off the data, captions name what is drawn"
              % count)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
