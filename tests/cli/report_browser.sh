#!/bin/sh
# The verification report opened in a real browser (headless Chromium).
#
# Runs `demvv verify --quick --only V1` (checks V10-V19: convergence tables,
# curves beside closed forms, margins; every check passes in its own ctest
# test, so the page is built from a subset to keep the suite short; one
# thread: a run beside other tests must not wait on busy cores), opens
# report.html and requires: no console
# message at all (the page writes none, so any is an error), every check
# section drawn with at least one figure, every figure rendered at a
# non-zero size (the page's own script marks each one), no figure missing,
# figures that cannot mislead (figure_lint.py: keys off the data and inside
# the picture, captions naming only what is drawn), a headline by V&V
# category with a banner (mode, date, commit, host, CPU),
# a scope, a sign-off block, every check folded and naming its case decks
# with their standard FNV-1a 64, and a screenshot that is not blank (pixels
# other than the background); then V25's own page, with its validation band
# and its uncertainty budget drawn.
#
# usage: report_browser.sh DEMVV WORK_DIR
set -eu
demvv=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "FAIL: no chromium on the PATH (Debian: apt-get install chromium)"
  exit 1
fi

"$demvv" verify --quick --only V1 --threads 1 --out "$work/report" > "$work/verify.log" 2>&1 || {
  echo "FAIL: demvv verify --quick --only V1 did not pass:"; tail -5 "$work/verify.log"; exit 1; }
page="file://$(cd "$work/report" && pwd)/report.html"

# HOME and the profile in the work folder: a fresh, private browser profile.
browse() {
  HOME="$work" timeout 120 "$browser" --headless --no-sandbox --disable-gpu --no-first-run \
    --user-data-dir="$work/profile" --virtual-time-budget=10000 --enable-logging=stderr --v=0 "$@"
}
browse --dump-dom "$page" > "$work/dom.html" 2> "$work/browser.log"
browse --window-size=1000,1600 --screenshot="$work/screenshot.png" "$page" > /dev/null 2>> "$work/browser.log"

fail=0
if grep -q "CONSOLE" "$work/browser.log"; then
  echo "FAIL: the page wrote to the console:"; grep "CONSOLE" "$work/browser.log"; fail=1
fi
body=$(grep -o '<body[^>]*>' "$work/dom.html" || true)
sections=$(grep -c '<section class="check"' "$work/dom.html" || true)
rendered=$(grep -o 'data-rendered="yes"' "$work/dom.html" | wc -l)
case "$body" in
  *'data-figures-missing="0"'*'data-figures-broken="0"'*) ;;
  *) echo "FAIL: figures missing or not rendered: $body"; fail=1 ;;
esac
figures=$(echo "$body" | sed -n 's/.*data-figures="\([0-9]*\)".*/\1/p')
if [ -z "$figures" ] || [ "$figures" -ne "$rendered" ] || [ "$sections" -eq 0 ] || [ "$rendered" -lt "$sections" ]; then
  echo "FAIL: $sections check sections, $figures figures, $rendered rendered (the load script did not run, or a check has no figure)"
  fail=1
fi
# The headline counts by V&V category, the banner says the mode, date,
# commit, host and CPU.
python3 - "$work/dom.html" <<'EOF' || fail=1
import re, sys
dom = open(sys.argv[1], encoding="utf-8").read()
head = re.search(r'<p id="headline"[^>]*>(.*?)</p>', dom, re.S)
banner = re.search(r'<p id="banner">(.*?)</p>', dom, re.S)
if not head or not re.search(r"code verification \d+/\d+ pass", head.group(1)):
    print("FAIL: no headline by category:", head.group(1) if head else "none")
    sys.exit(1)
if not banner or not all(w in banner.group(1) for w in ("Quick mode", "commit", "Run ")):
    print("FAIL: no banner with mode, date and commit:", banner.group(1) if banner else "none")
    sys.exit(1)
EOF
# A signable page: the scope and intended use, a sign-off block with its
# roles, every check folded in a <details> (open when it fails) that names
# its case decks, and each case deck's hash the standard FNV-1a 64 of the
# deck's text (recomputed here from the file).
python3 - "$work/dom.html" "$(dirname "$0")/../../cases" <<'EOF' || fail=1
import re, sys
dom, cases = open(sys.argv[1], encoding="utf-8").read(), sys.argv[2]
for needed in ("Scope and intended use", 'id="sign-off"', "reviewed by", "approved by"):
    if needed not in dom:
        print("FAIL: the page lacks", repr(needed)); sys.exit(1)
parts = dom.split('<section class="check"')[1:]
for p in parts:
    part = p.split("</section>")[0]
    ident = re.search(r'id="([^"]+)"', p).group(1)
    folded = re.search(r"<details( open)?", part)
    failing = 'class="fail">FAIL' in part.split("</summary>")[0]
    if not folded or bool(folded.group(1)) != failing:
        print("FAIL: %s is not folded as its verdict asks (open only when it fails)" % ident); sys.exit(1)
    if "Case decks</dt>" not in part:
        print("FAIL: %s does not name its case decks" % ident); sys.exit(1)
# (?<!...): a name starts where a run of name characters starts, so the
# search is linear in the page (figures are embedded as base64, whose runs
# of letters reach a megabyte).
hashes = re.findall(r"(?<![\w.])([\w.]+/case\.prm) \(FNV-1a 64 ([0-9a-f]{16})\)", dom)
if not hashes:
    print("FAIL: no case deck hash on the page"); sys.exit(1)
for path, shown in hashes:
    h = 14695981039346656037
    for b in open(cases + "/" + path, "rb").read():
        h = ((h ^ b) * 1099511628211) % 2**64
    if "%016x" % h != shown:
        print("FAIL: %s's hash %s is not the FNV-1a 64 of its text (%016x)" % (path, shown, h)); sys.exit(1)
EOF
# Figures that cannot mislead: each key inside its picture, off the data
# and the labels, each caption naming only what its figure draws
# (figure_lint.py reads the figures the browser was given).
python3 "$(dirname "$0")/figure_lint.py" "$work/dom.html" || fail=1
# Every check section holds a rendered figure.
python3 - "$work/dom.html" <<'EOF' || fail=1
import re, sys
dom = open(sys.argv[1], encoding="utf-8").read()
parts = dom.split('<section class="check"')[1:]
bare = [re.search(r'id="([^"]+)"', p).group(1) for p in parts if 'data-rendered="yes"' not in p.split("</section>")[0]]
if bare:
    print("FAIL: check sections without a rendered figure:", ", ".join(bare))
    sys.exit(1)
EOF
# The screenshot is not blank: decode the PNG (zlib + scanline filters) and
# count pixels that differ from the top-left (background) pixel.
python3 - "$work/screenshot.png" <<'EOF' || fail=1
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, head = 8, b"", None
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    chunk = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        head = struct.unpack(">IIBBBBB", chunk)
    elif kind == b"IDAT":
        idat += chunk
    pos += n + 12
width, height, depth, colour = head[:4]
assert depth == 8 and colour in (2, 6), "unexpected PNG format"
bpp = 3 if colour == 2 else 4
raw, stride = zlib.decompress(idat), width * bpp
prev, rows, k = bytearray(stride), [], 0
for _ in range(height):
    f, line = raw[k], bytearray(raw[k + 1:k + 1 + stride])
    k += 1 + stride
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b, c = prev[i], prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    prev = line
background = bytes(rows[0][:3])
differing = sum(1 for r in rows for x in range(0, stride, bpp) if bytes(r[x:x + 3]) != background)
share = differing / (width * height)
if share < 0.01:
    print("FAIL: the screenshot is blank (%.4f of pixels differ from the background)" % share)
    sys.exit(1)
print("screenshot: %.1f %% of pixels drawn" % (100 * share))
EOF

# The validation check's page (V25, its own report: a pattern selects one
# set of checks): the comparison with its 2 u_val band and the uncertainty
# budget part by part are drawn at a non-zero size.
"$demvv" verify --quick --only V25 --threads 1 --out "$work/validation" > "$work/validation.log" 2>&1 || {
  echo "FAIL: demvv verify --quick --only V25 did not run:"; tail -5 "$work/validation.log"; exit 1; }
browse --dump-dom "file://$(cd "$work/validation" && pwd)/report.html" > "$work/validation_dom.html" \
  2> "$work/validation_browser.log"
python3 - "$work/validation_dom.html" <<'EOF' || fail=1
import re, sys
dom = open(sys.argv[1], encoding="utf-8").read()
body = re.search(r"<body[^>]*>", dom).group(0)
if 'data-figures-missing="0"' not in body or 'data-figures-broken="0"' not in body:
    print("FAIL: V25's page has figures missing or broken: " + body)
    sys.exit(1)
for title in ("Peak stress against the temperature-compensated rate",
              "The validation uncertainty budget, part by part"):
    img = [t for t in re.findall(r"<img[^>]*>", dom) if 'alt="' + title in t]
    if not img or 'data-rendered="yes"' not in img[0]:
        print("FAIL: V25's figure '%s' is not drawn on its page" % title)
        sys.exit(1)
print("V25: the validation band and the budget figures drawn")
EOF
python3 "$(dirname "$0")/figure_lint.py" "$work/validation_dom.html" || fail=1
[ "$fail" -eq 0 ] && echo "report.html: $sections checks, $rendered figures rendered, no console message"
exit "$fail"
