"""An HTML page as Debian's chromium renders it, headless: the DOM its scripts leave and the
console's errors. The report tests check what a user's browser shows with it."""
import shutil
import subprocess
import tempfile

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run", "--hide-scrollbars"]


def chromium():
    """The browser's path, or None when it is not installed."""
    return shutil.which("chromium") or shutil.which("chromium-browser")


def render(page, browser=None):
    """(exit status, the DOM after 5 s of the page's virtual time, the console's error lines)."""
    browser = browser or chromium()
    with tempfile.TemporaryDirectory() as profile:
        r = subprocess.run([browser, *FLAGS, "--user-data-dir=" + profile, "--enable-logging=stderr",
                            "--v=0", "--virtual-time-budget=5000", "--dump-dom", "file://" + page],
                           capture_output=True, text=True, timeout=180)
    errors = [l for l in r.stderr.splitlines()
              if "Uncaught" in l or ("CONSOLE" in l and "rror" in l)]
    return r.returncode, r.stdout, errors
