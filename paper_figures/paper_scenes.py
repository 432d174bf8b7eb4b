"""The papers' scenes as their tables give them, beside the testbed's: the one place for the papers'
scene counts (Walewski 2019 Table 4, Sabino 2012 Tables 3 and 4, de Macedo & Rodrigues Tables I
and II with their frame times) and what Hakura & Snyder say of theirs, with why the testbed's
scenes differ. Each paper-table script prints scene_count_lines(rows, paper) under its tables; the
testbed's counts come from the records (scene_stats; the dynamic triangles from the ray scene's
counters, bvh_moving_triangles + bvh_refit_triangles)."""
import collections

# A count's key in a record's scene_stats (or DYNAMIC), and its name in the lines.
DYNAMIC = "dynamic_triangles"
COUNT_NAMES = {"triangles": "triangles", DYNAMIC: "dynamic triangles", "vertices": "vertices", "objects": "objects",
               "reflective": "reflective", "refractive": "refractive"}
# Counts compared as a ratio (here / paper); the others are small numbers, read side by side.
RATIO_COUNTS = ("triangles", DYNAMIC, "vertices")

# A paper's scene: its name there, its counts (None where the paper does not give one), why the
# testbed's scene of that name differs, and the name that line gives the scene (one for a family
# of scenes that differ alike).
PaperScene = collections.namedtuple("PaperScene", "name counts differs group")
# A paper's scenes by the testbed's scene names; `thousands`: the paper gives counts in thousands to
# one decimal.
Paper = collections.namedtuple("Paper", "title scenes thousands")

_SPONZA = ("the committed Sponza is the 66,444-triangle Dabrovic atrium, where the paper's %s has the size of "
           "Crytek's Sponza (about 262k triangles), which is not in the repository")


def _walewski():
    return Paper("Walewski 2019 Table 4", {
        "sponza-spheres": PaperScene(
            "Sponza Spheres", {"triangles": 272144, "vertices": 150704, "objects": 29, "reflective": 3, "refractive": 23},
            (_SPONZA % "scene (272,144 triangles with the spheres)") + "; the 3 mirror and 23 glass spheres are the paper's, "
            "and Sponza is one object here where the paper counts 29 objects in all", "sponza-spheres"),
        "sponza-armadillo": PaperScene(
            "Sponza Armadillo", {"triangles": 292544, "vertices": 160896, "objects": 25, "reflective": 0, "refractive": 21},
            "the same Sponza, and the full-resolution Stanford armadillo (345,944 triangles) where the paper's is about 30k "
            "(its 292,544 less Sponza's); the paper counts 21 refractive objects without naming them, here the armadillo is the one",
            "sponza-armadillo"),
        "dining-room": PaperScene(
            "Dining Room", {"triangles": 139378, "vertices": 71697, "objects": 27, "reflective": 0, "refractive": 1},
            "the paper's dining room is not public: Bitterli's breakfast room (Wig42, 269,538 triangles in 53 meshes, one "
            "object here) stands in for it, with the paper's one glass object, a ball", "dining-room"),
    }, False)


def _sabino():
    return Paper("Sabino 2012 Tables 3 and 4", {
        "sponza-spheres": PaperScene(
            "Sponza (Table 3)", {"triangles": 262187, "vertices": 145173},
            (_SPONZA % "Sponza (262,187 triangles)") + "; the spheres give it the reflective and refractive objects the paper's Figure 5(a) shows",
            "sponza-spheres"),
        "sponza-armadillo": PaperScene(
            "Armadillo (Table 3)", {"triangles": 380655, "vertices": 193737},
            "the paper's armadillo stands in an open environment (its Section 8: rays escape), here the full-resolution "
            "glass armadillo stands in the closed Sponza atrium", "sponza-armadillo"),
        "dining-room": PaperScene(
            "Dining Room (Table 4)", {"triangles": 224954, "vertices": 386541},
            "the paper's is Brigade's demo scene, not public: Bitterli's breakfast room stands in for it", "dining-room"),
    }, False)


# de Macedo & Rodrigues Tables I and II: N, triangles and dynamic triangles (x10^3), frame time mean,
# standard deviation, min and max (ms), implementation (the paper's rows, in its order).
MACEDO_TABLE_I = [
    (5, 3.2, 2.5, 15.2, 0.7, 14.0, 17.7, "CUDA"), (10, 5.7, 5.0, 18.4, 1.1, 16.1, 21.5, "CUDA"),
    (15, 8.2, 7.5, 22.6, 1.2, 21.0, 26.5, "CUDA"), (20, 10.7, 10.0, 28.9, 1.4, 25.5, 32.4, "CUDA"),
    (25, 13.2, 12.5, 31.7, 1.6, 29.6, 37.7, "CUDA"), (30, 15.7, 15.0, 36.5, 1.5, 34.4, 43.7, "CUDA"),
    (5, 3.2, 2.5, 39.1, 2.1, 36.2, 46.5, "OptiX"), (10, 5.7, 5.0, 55.1, 2.6, 52.7, 63.5, "OptiX"),
    (15, 8.2, 7.5, 75.7, 3.7, 70.6, 94.0, "OptiX"), (20, 10.7, 10.0, 98.6, 3.7, 88.2, 113.3, "OptiX"),
    (25, 13.2, 12.5, 111.1, 5.3, 104.0, 135.3, "OptiX"), (30, 15.7, 15.0, 129.3, 6.8, 122.1, 163.9, "OptiX"),
]
MACEDO_TABLE_II = [
    # The paper prints "13.6, 13.6" as min and max of its first row (mean 14.7).
    (5, 3.0, 2.8, 14.7, 0.8, 13.6, 13.6, "CUDA"), (10, 5.9, 5.7, 21.9, 1.2, 20.5, 26.5, "CUDA"),
    (15, 8.8, 8.6, 28.4, 1.1, 26.5, 31.1, "CUDA"), (20, 11.6, 11.4, 36.4, 1.5, 33.8, 41.5, "CUDA"),
    (25, 14.5, 14.3, 44.3, 2.0, 40.6, 51.7, "CUDA"), (30, 17.4, 17.2, 50.0, 1.9, 45.4, 55.1, "CUDA"),
    (5, 3.0, 2.8, 40.9, 0.7, 39.8, 43.5, "OptiX"), (10, 5.9, 5.7, 59.5, 2.7, 56.0, 66.3, "OptiX"),
    (15, 8.8, 8.6, 80.7, 2.9, 76.0, 88.2, "OptiX"), (20, 11.6, 11.4, 103.3, 3.9, 95.9, 115.0, "OptiX"),
    (25, 14.5, 14.3, 117.0, 4.4, 113.0, 136.6, "OptiX"), (30, 17.4, 17.2, 138.7, 6.5, 132.9, 159.1, "OptiX"),
]
MacedoRow = collections.namedtuple("MacedoRow", "n triangles_k dynamic_k mean_ms std_ms min_ms max_ms implementation")
# The testbed's scene family of each table, and what its objects are.
MACEDO_FAMILIES = {"I": ("bunnies-falling", "Stanford bunnies", MACEDO_TABLE_I),
                   "II": ("teapots-deforming", "Utah teapots", MACEDO_TABLE_II)}
_MACEDO_DIFFERS = {
    "I": "the bunny is the Stanford bunny simplified to 500 triangles by gltfpack (scenes/assets), the mirror sphere has "
         "728 triangles and the floor 2, the paper's sizes within its rounding; the paper does not say how its bunnies "
         "fall, here each bounces on the floor along the same keyframes, later by 0.06 s than the one before",
    "II": "the teapot is the closed Utah teapot simplified to 572 triangles by gltfpack (scenes/assets), the mirror sphere "
          "has 224 triangles and the floor 2, the paper's sizes within its rounding; the paper does not say how its teapots "
          "deform, here each by a travelling wave (scenes/README.md, deform)",
}


def macedo_rows(table):
    """Table I or II of de Macedo & Rodrigues as MacedoRows."""
    return [MacedoRow(*r) for r in MACEDO_FAMILIES[table][2]]


def _macedo():
    scenes = {}
    for table, (family, what, rows) in MACEDO_FAMILIES.items():
        for row in map(lambda r: MacedoRow(*r), rows):
            if row.implementation == "CUDA":
                scenes["%s-%d" % (family, row.n)] = PaperScene(
                    "Table %s, %d %s" % (table, row.n, what),
                    {"triangles": row.triangles_k * 1e3, DYNAMIC: row.dynamic_k * 1e3}, _MACEDO_DIFFERS[table], family + "-N")
    return Paper("de Macedo & Rodrigues Tables I and II", scenes, True)


def _hakura():
    return Paper("Hakura & Snyder 2001 Section 6", {
        "teapot-lens": PaperScene(
            "a glass teapot, a reflective cup, a ring of columns and distant walls",
            {"triangles": None, "vertices": None, "objects": None, "reflective": 1, "refractive": 1},
            "the paper gives no triangle, vertex or column counts; here the full-resolution teapot (15,704 triangles), "
            "a cup, 8 columns and 4 walls", "teapot-lens"),
    }, False)


PAPERS = {"walewski2019": _walewski(), "sabino2012": _sabino(), "macedo2019": _macedo(), "hakura2001": _hakura()}


def counts_here(r):
    """A record's scene counts: its scene_stats, and its dynamic triangles where the ray scene counted them."""
    counts = dict(r["scene_stats"])
    c = r.get("counters", {})
    if "bvh_moving_triangles" in c or "bvh_refit_triangles" in c:
        counts[DYNAMIC] = c.get("bvh_moving_triangles", 0.0) + c.get("bvh_refit_triangles", 0.0)
    return counts


def _number(value, thousands):
    if value is None:
        return "not given"
    return "%.2fk" % (value / 1e3) if thousands else "{:,}".format(int(round(value)))


def _paper_number(value, thousands):
    # The paper's own precision: thousands to one decimal where it gives them so.
    if value is None:
        return "not given"
    return "%.1fk" % (value / 1e3) if thousands else "{:,}".format(int(round(value)))


def count_cells(here, paper_counts, thousands):
    """`name here / paper` for each count the paper's scene lists, with the ratio here / paper for the large ones."""
    cells = []
    for key, theirs in paper_counts.items():
        ours = here.get(key)
        cell = "%s %s / %s" % (COUNT_NAMES[key], "-" if ours is None else _number(ours, thousands), _paper_number(theirs, thousands))
        if key in RATIO_COUNTS and ours is not None and theirs:
            cell += " (%.2fx)" % (ours / theirs)
        cells.append(cell)
    return ", ".join(cells)


def scene_count_lines(rows, paper):
    """The lines under a table of `paper` (a PAPERS key): for each scene of `rows` the paper describes,
    in the order of their first run, its counts here beside the paper's; then one line on what differs
    and why. [] when the rows hold none of the paper's scenes."""
    p = PAPERS[paper]
    first = {}
    for r in rows:
        if r["scene"] in p.scenes:
            first.setdefault(r["scene"], r)
    if not first:
        return []
    out = ["", "Scene counts, here / %s:" % p.title, ""]
    for scene, r in first.items():
        s = p.scenes[scene]
        out.append("- %s / %s: %s" % (scene, s.name, count_cells(counts_here(r), s.counts, p.thousands)))
    differs = []
    for scene in first:
        line = "%s: %s" % (p.scenes[scene].group, p.scenes[scene].differs)
        if line not in differs:
            differs.append(line)
    out += ["", "What differs and why: %s." % "; ".join(differs), ""]
    return out
