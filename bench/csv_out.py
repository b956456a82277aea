"""CSV output shared by the bench scripts: one row per dict, the columns in the first row's order."""
import csv
import os


def write_csv(path, rows):
    """Writes `rows` (dicts with the same keys) to `path`, creating its folder, and says so."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print('wrote', path)
