"""HTML printed to PDF by a headless Chromium (Debian's ``chromium``;
``make browser`` installs it), written atomically and marked as judder's.

The strings of :data:`CHROMIUM_FLAGS` are Chromium's command line, not
the project's.
"""

from pathlib import Path
import shutil
import subprocess
import tempfile

from .errors import JudderError
from .files import atomic_write, mark_pdf


#: Flags of a headless Chromium that reads only the given file.
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu",
                  "--disable-background-networking",
                  "--disable-component-update", "--disable-sync",
                  "--no-first-run", "--no-pdf-header-footer")


def print_pdf(html_path, pdf_path):
    """Print an HTML file to PDF with headless Chromium, atomically.

    Raises
    ------
    JudderError
        No Chromium on the PATH, or it failed.
    """
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        raise JudderError("`pdf` needs Chromium (Debian: apt-get install "
                          "chromium, or make browser); the HTML report "
                          "was written")
    with tempfile.TemporaryDirectory() as scratch:
        target = Path(scratch) / "report.pdf"
        proc = subprocess.run(
            [browser, *CHROMIUM_FLAGS, f"--user-data-dir={scratch}/profile",
             f"--print-to-pdf={target}", Path(html_path).resolve().as_uri()],
            capture_output=True, text=True, timeout=300)
        if not target.exists() or target.stat().st_size == 0:
            raise JudderError(f"`pdf`: chromium could not print the report "
                              f"(exit {proc.returncode})")
        # marked, so that the next run may replace it (the overwrite rule)
        data = mark_pdf(target.read_bytes())
    atomic_write(pdf_path, lambda stream: stream.write(data))
