"""Write docs/validation.md from validation/ (run from the repository root:
python -m scripts.make_validation)."""

from stripcoef.files import write_text
from validation import ROOT, build

if __name__ == "__main__":
    out = ROOT / "docs" / "validation.md"
    write_text(out, build())
    print(f"wrote {out}")
