"""Write docs/export/examples/: every text export of geometry/mares.yaml, with its warnings.

Run: python -m scripts.make_export_examples
"""

import dataclasses
import warnings
from pathlib import Path

import stripcoef
from stripcoef.export import FORMATS, write_export

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "export" / "examples"

# (file name, format, options)
EXAMPLES = [
    ("mares.sdf", "gazebo", {}),
    ("mares_legacy.sdf", "gazebo", {"legacy_added_mass": True}),
    ("mares_uuv.xml", "uuv", {}),
    ("mares.m", "mss", {}),
    ("mares_model.py", "python", {}),
    ("mares.json", "json", {}),
    ("mares.yaml", "yaml", {}),
    ("mares.csv", "csv", {}),
]

if __name__ == "__main__":
    model = stripcoef.estimate(stripcoef.load_vehicle(ROOT / "geometry" / "mares.yaml"))
    # the checkout's absolute path would differ per machine: name the file relative to the root
    model = dataclasses.replace(model, provenance={**model.provenance,
                                                   "source": "geometry/mares.yaml"})
    notes = []
    for name, fmt, options in EXAMPLES:
        assert not FORMATS[fmt].binary
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            write_export(model, fmt, OUT / name, **options)
        for w in caught:
            notes.append(f"{name}: {w.category.__name__}: {w.message}")
        print(f"wrote {OUT / name}")
    (OUT / "warnings.txt").write_text("\n".join(notes) + "\n")
    print(f"wrote {OUT / 'warnings.txt'}")
