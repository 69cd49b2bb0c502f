"""The documentation site: built with warnings as errors (the README's
command, from a fresh environment), every public name in its API reference,
and the landing page, an API page and a notebook page opened in headless
Chromium (Debian's chromium and chromium-driver; nothing is downloaded) with
every image loaded. Screenshots go to ``docs/_build/screenshots``."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

import topomesh

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
HTML = DOCS / "_build" / "html"
SHOTS = DOCS / "_build" / "screenshots"
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
#: the README's command, plus -E: every page is re-read, so every warning is seen
BUILD = [sys.executable, "-m", "sphinx", "-E", "-W", "--keep-going", "-b", "html", "docs", str(HTML.relative_to(ROOT))]


@pytest.fixture(scope="session")
def site() -> Path:
    env = dict(os.environ, VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow", MPLBACKEND="Agg")
    t0 = time.perf_counter()
    r = subprocess.run(BUILD, cwd=ROOT, env=env, capture_output=True, text=True, timeout=1200)
    seconds = time.perf_counter() - t0
    if r.returncode != 0:
        warnings = [line for line in (r.stdout + r.stderr).splitlines() if "WARNING" in line or "ERROR" in line or "Error" in line]
        pytest.fail(f"docs build failed ({r.returncode}) after {seconds:.0f} s:\n" + "\n".join(warnings[-40:] or (r.stderr or r.stdout).splitlines()[-40:]))
    SHOTS.mkdir(parents=True, exist_ok=True)
    (SHOTS / "timings.json").write_text(json.dumps({"docs_build_s": round(seconds, 1)}))
    return HTML


def _inventory(site: Path) -> set[str]:
    from sphinx.util.inventory import InventoryFile

    with open(site / "objects.inv", "rb") as f:
        inv = InventoryFile.load(f, "", lambda base, uri: uri)
    return {name for role, items in inv.items() if role.startswith("py:") for name in items}


def test_reference_has_every_public_name(site: Path) -> None:
    names = _inventory(site)
    wanted = [f"topomesh.{n}" for n in topomesh.__all__]
    for cls in (topomesh.Mesh, topomesh.Rind):
        wanted += [f"topomesh.{cls.__name__}.{m}" for m in dir(cls) if not m.startswith("_")]
    wanted += ["topomesh.Mesh._repr_html_", "topomesh.Mesh._repr_png_"]
    wanted += [f"topomesh.ifs.{n}" for n in topomesh.ifs.__all__]
    wanted += [f"topomesh.ifs.IFS.{m}" for m in dir(topomesh.ifs.IFS) if not m.startswith("_")]
    missing = [n for n in wanted if n not in names]
    assert not missing, f"not in the API reference (docs/api/*.rst): {', '.join(missing)}"


def test_reference_signatures_from_stubs(site: Path) -> None:
    import html as html_mod
    import re

    page = (site / "api" / "mesh.html").read_text()
    text = html_mod.unescape(re.sub(r"<[^>]+>", "", page))
    # typed parameters and return types exist only in python/topomesh/_core.pyi
    assert "honeycomb(iterations: int = 1, t: float = 0.5, tension: float | None = None, progress: bool = False, *, correspondence: Literal[False] = False) → Mesh" in text
    assert "triangles(return_faces: Literal[True]) -> tuple[" in text  # the second overload
    assert "Type (from the stubs): npt.NDArray[np.float64]" in text  # Mesh.vertices


def test_notebooks_rendered_static(site: Path) -> None:
    """Every notebook is a page with its outputs as images; the explorer of
    03_subdivision is a PNG, not a widget view (no widget JavaScript)."""
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        page = (site / "notebooks" / f"{nb.stem}.html").read_text()
        assert page.count("<img ") >= 2, f"{nb.name}: no rendered image output"
        assert "widget-view+json" not in page and "embed-amd.js" not in page, nb.name
        assert "Traceback" not in page, nb.name


def _driver():  # type: ignore[no-untyped-def]
    if not (Path(CHROMIUM).exists() and Path(CHROMEDRIVER).exists()):
        pytest.skip("Debian's chromium and chromium-driver are not installed (.ci/setup installs them as root)")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    # an explicit driver and browser: selenium-manager (which downloads) never runs
    os.environ.setdefault("SE_AVOID_STATS", "true")
    os.environ.setdefault("SE_OFFLINE", "true")
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1280,1100",
              "--allow-file-access-from-files", "--hide-scrollbars"):
        opts.add_argument(a)
    opts.set_capability("goog:loggingPrefs", {"browser": "SEVERE"})
    return webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=opts)


def _images(driver) -> list[dict[str, object]]:  # type: ignore[no-untyped-def]
    return driver.execute_script(
        "return Array.from(document.images).map(i => ({src: i.currentSrc.slice(0, 120), complete: i.complete, width: i.naturalWidth}));"
    )


@pytest.mark.parametrize(
    "page, title, heading, min_images",
    [
        ("index.html", "topomesh", "topomesh", 3),
        ("api/mesh.html", "Mesh", "Mesh", 0),
        ("notebooks/03_subdivision.html", "Subdivision", "Subdivision: honeycomb and vertex truncation", 15),
    ],
    ids=["landing", "api", "notebook"],
)
def test_browser_pages(site: Path, page: str, title: str, heading: str, min_images: int) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    path = site / page
    assert path.is_file(), f"{page} was not built"
    driver = _driver()
    try:
        driver.get(path.as_uri())
        assert title in driver.title, f"{page}: title {driver.title!r}"
        h1 = driver.find_element(By.TAG_NAME, "h1").text
        assert h1.startswith(heading), f"{page}: first heading {h1!r}"
        # bring every image into view once, then wait for all to decode
        driver.execute_script("for (const i of document.images) { i.loading = 'eager'; }")
        height = driver.execute_script("return document.body.scrollHeight")
        for y in range(0, int(height), 800):
            driver.execute_script(f"window.scrollTo(0, {y});")
        WebDriverWait(driver, 30).until(lambda d: all(i["complete"] for i in _images(d)))
        imgs = _images(driver)
        broken = [i["src"] for i in imgs if not i["width"]]
        assert not broken, f"{page}: images not loaded: {broken}"
        assert len(imgs) >= min_images, f"{page}: {len(imgs)} images, expected at least {min_images}"
        # a self-contained site: nothing fetched from the network (MathJax is served locally)
        remote = driver.execute_script(
            "return performance.getEntriesByType('resource').map(e => e.name).filter(n => !n.startsWith('file:') && !n.startsWith('data:'));"
        )
        assert not remote, f"{page}: fetched from the network: {remote}"
        errors = [e["message"] for e in driver.get_log("browser") if e.get("level") == "SEVERE"]
        assert not errors, f"{page}: browser errors: {errors}"
        SHOTS.mkdir(parents=True, exist_ok=True)
        name = page.replace("/", "_").removesuffix(".html")
        # the theme scrolls smoothly: jump instead, so a screenshot is not taken mid-scroll
        # (re-issued at every poll: a smooth scroll still in flight, or scroll anchoring as late images decode,
        # can move the page after one jump; CI once timed out on a single jump)
        driver.execute_script("document.documentElement.style.scrollBehavior = 'auto';")
        top = "window.scrollTo({top: 0, left: 0, behavior: 'instant'}); return window.scrollY"
        WebDriverWait(driver, 15).until(lambda d: abs(d.execute_script(top)) < 1)
        assert driver.save_screenshot(str(SHOTS / f"{name}.png"))
        if page.startswith("notebooks/"):
            # the live-parameters section: the explorer, rendered as its image
            section = driver.find_element(By.ID, "live-parameters-topomesh-explore-and-mesh-plot")
            first = section.find_element(By.TAG_NAME, "img")
            driver.execute_script("arguments[0].scrollIntoView({block: 'center', behavior: 'instant'});", first)
            assert driver.save_screenshot(str(SHOTS / f"{name}_explore.png"))
    finally:
        driver.quit()


#: the sources each scheme page's formulas are taken from (module docs of the Rust schemes, the docs pages)
FORMULA_SOURCES = {
    "schemes/subdivision.md": ["src/schemes/catmull_clark.rs", "src/schemes/doo_sabin/mod.rs", "src/schemes/doo_sabin/open.rs", "src/schemes/loop_subdivision.rs",
                               "src/schemes/sqrt3/mod.rs", "src/schemes/sqrt3/boundary.rs", "src/schemes/simplest/mod.rs", "src/schemes/midpoint.rs", "src/schemes/dual.rs"],
    "schemes/high_genus.md": ["src/schemes/honeycomb.rs", "src/schemes/vertex_truncation.rs", "docs/ops.md"],
    "schemes/sierpinski.md": ["src/schemes/sierpinski.rs"],
    "schemes/menger.md": ["src/schemes/menger/mod.rs", "src/schemes/menger_sponge/mod.rs"],
    "schemes/ifs.md": ["docs/ifs.md", "python/topomesh/ifs.py"],
}


def _norm(s: str) -> str:
    import re

    s = s.replace("`", "").replace("′", "'").replace("//!", " ")
    return re.sub(r"\s+", " ", s).strip()


def _formula_pieces(page: str) -> list[str]:
    """The formulas a scheme page states: every line of its ```text blocks
    (split where columns are aligned) and every cell of its count tables
    (tables whose header names V′)."""
    import re

    pieces: list[str] = []
    for block in re.findall(r"```text\n(.*?)```", page, flags=re.S):
        for line in block.splitlines():
            pieces += [p for p in re.split(r"\s{2,}", line.strip()) if p]
    header: list[str] = []
    for line in page.splitlines():
        if not line.startswith("|"):
            header = []
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not header:
            header = cells
        elif not set(line) <= set("|- ") and any("V′" in h for h in header):
            pieces += [c for c in cells if c]
    return pieces


@pytest.mark.parametrize("page", sorted(FORMULA_SOURCES))
def test_scheme_formulas_come_from_the_code_docs(page: str) -> None:
    """Nothing on a scheme page's formula blocks and count tables is
    invented: each piece is in the module docs (or docs page) it cites."""
    sources = _norm("\n".join((ROOT / s).read_text() for s in FORMULA_SOURCES[page]))
    pieces = _formula_pieces((DOCS / page).read_text())
    assert pieces, f"{page}: no formulas found"
    missing = [p for p in pieces if _norm(p) not in sources]
    assert not missing, f"{page}: not in {', '.join(FORMULA_SOURCES[page])}: {missing}"
