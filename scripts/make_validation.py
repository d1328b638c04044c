"""Write docs/validation.md from stripcoef.report (run: python scripts/make_validation.py)."""

from pathlib import Path

from stripcoef.io import write_text
from stripcoef.report import build

if __name__ == "__main__":
    out = Path(__file__).resolve().parent.parent / "docs" / "validation.md"
    write_text(out, build())
    print(f"wrote {out}")
