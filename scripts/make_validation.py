"""Write docs/validation.md from validation/ (run: python scripts/make_validation.py)."""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))   # validation/ lives beside src/, out of the wheel

from stripcoef.files import write_text  # noqa: E402
from validation import build  # noqa: E402

if __name__ == "__main__":
    out = ROOT / "docs" / "validation.md"
    write_text(out, build())
    print(f"wrote {out}")
