"""The report: summary.json has the fixed schema; index.html is well formed, links only relative
paths, and every image it shows exists."""
import html.parser
import json
import os
from urllib.parse import urlparse

ENGINES = {"BXDF_LAB", "CYCLES", "POVRAY_RENDER", "ANALYTIC"}
VOID = {"meta", "img", "br", "hr", "link", "input"}


class _Checker(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.stack, self.errors, self.images, self.links = [], [], [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images.append(attrs.get("src"))
            if not attrs.get("alt"):
                self.errors.append(f"img without alt: {attrs}")
        if tag == "a" and "href" in attrs:
            self.links.append(attrs["href"])
        if tag not in VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        if tag in VOID:
            return
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes {self.stack[-1:] or 'nothing'}")
        else:
            self.stack.pop()


def test_summary_json_schema(main_run):
    run_dir, summary = main_run
    with open(os.path.join(run_dir, "summary.json"), encoding="utf-8") as fh:
        json.loads(fh.read(), parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
    assert summary["scenes"]
    for entry in summary["scenes"]:
        assert isinstance(entry["name"], str)
        assert set(entry["engines"]) <= ENGINES
        for engine in entry["engines"].values():
            assert engine["status"] in ("ok", "failed")
            assert "seconds" in engine and "image" in engine
        lab, cycles = entry["engines"]["BXDF_LAB"], entry["engines"]["CYCLES"]
        assert abs(lab["time_vs_cycles"] * cycles["seconds"] - lab["seconds"]) < 1e-9
        assert entry["pairings"]
        for p in entry["pairings"]:
            assert {"a", "b", "label", "rmse", "z_fail_fraction", "pass"} <= set(p)
            assert p["a"] in ENGINES and p["b"] in ENGINES and p["a"] != p["b"]
            assert p["label"] in ("exact", "approximate")
            assert isinstance(p["pass"], bool)
            assert p["rmse"] >= 0 and 0 <= p["z_fail_fraction"] <= 1
            for key in ("mean", "max_abs", "psnr", "rel_mse"):
                assert key in p


def test_index_html_is_well_formed_and_every_image_exists(main_run):
    run_dir, summary = main_run
    with open(os.path.join(run_dir, "index.html"), encoding="utf-8") as fh:
        page = fh.read()
    checker = _Checker()
    checker.feed(page)
    checker.close()
    assert not checker.errors, checker.errors[:5]
    assert checker.stack == [], checker.stack
    for ref in checker.images + checker.links:
        if ref.startswith("#"):
            continue
        parsed = urlparse(ref)
        assert not parsed.scheme and not ref.startswith("/"), f"not relative: {ref}"
        assert os.path.isfile(os.path.join(run_dir, ref)), f"missing: {ref}"
    # Every rendered image and heat map of the summary is shown on the page.
    for entry in summary["scenes"]:
        for name, engine in entry["engines"].items():
            if engine["status"] == "ok":
                assert engine["display"] in checker.images, (entry["name"], name)
                assert engine["image"] in checker.links
        for p in entry["pairings"]:
            assert p["heatmap"] in checker.images
    assert any(src.startswith("report/materials/") for src in checker.images)
    assert "Render time against Cycles" in page and "BXDF_LAB / CYCLES" in page


def test_a_run_with_override_says_so_in_the_page(main_run):
    run_dir, _ = main_run
    with open(os.path.join(run_dir, "index.html"), encoding="utf-8") as fh:
        page = fh.read()
    assert "This run used --override" in page
    assert "POVRAY_RENDER: material lambert_grey: reflectance = [0.68, 0.68, 0.68]" in page
