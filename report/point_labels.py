"""Labels beside chart points that overlap neither each other nor the points: each label tries
positions around its point, nearest first, and takes the first whose box (in display pixels,
measured after drawing) is clear of the labels already placed, the points and the axes' edge;
where none is clear within reach it goes to the clear position nearest the point, with a leader
line."""
import math

# Offsets tried around a point, in points: rings of eight directions, growing outwards.
RINGS = (6, 12, 20, 30, 44, 60, 80, 105)
DIRECTIONS = [(1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)]
POINT_RADIUS_PX = 3.0
LABEL = "point label"  # the annotations' artist label, by which a test finds them


def overlaps(a, b, pad=1.0):
    return not (a.x1 + pad <= b.x0 or b.x1 + pad <= a.x0 or a.y1 + pad <= b.y0 or b.y1 + pad <= a.y0)


def hits_point(box, points_px):
    return any(box.x0 - POINT_RADIUS_PX < x < box.x1 + POINT_RADIUS_PX and box.y0 - POINT_RADIUS_PX < y < box.y1 + POINT_RADIUS_PX
               for x, y in points_px)


def place(ax, points, texts, fontsize=7):
    """Annotates point i (data coordinates) with texts[i]; returns the annotations."""
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    to_px = ax.transData.transform
    points_px = [tuple(to_px(p)) for p in points]
    frame = ax.get_window_extent(renderer)
    placed, notes = [], []
    for (x, y), text in sorted(zip(points, texts), key=lambda pt: to_px(pt[0])[0]):
        note = ax.annotate(text, (x, y), xytext=(0, 0), textcoords="offset points", fontsize=fontsize, ha="center", va="center",
                           bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8), annotation_clip=False)
        note.set_label(LABEL)
        chosen = None
        for ring in RINGS:
            for dx, dy in DIRECTIONS:
                norm = math.hypot(dx, dy)
                note.set_position((ring * dx / norm, ring * dy / norm))
                box = note.get_window_extent(renderer)
                inside = frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
                if inside and not hits_point(box, points_px) and not any(overlaps(box, b) for b in placed):
                    chosen = box
                    break
            if chosen:
                break
        if chosen is None:
            # Crowded: search farther out on a finer ring, anywhere inside the figure.
            for radius in range(120, 600, 15):
                for k in range(24):
                    angle = 2 * math.pi * k / 24
                    note.set_position((radius * math.cos(angle), radius * math.sin(angle)))
                    box = note.get_window_extent(renderer)
                    if not hits_point(box, points_px) and not any(overlaps(box, b) for b in placed):
                        chosen = box
                        break
                if chosen:
                    break
        if chosen is None:
            chosen = note.get_window_extent(renderer)
        offset = note.get_position()
        if math.hypot(*offset) > 14:
            # A leader line, as its own artist so that the label's box stays the text's.
            ax.annotate("", (x, y), xytext=offset, textcoords="offset points", annotation_clip=False,
                        arrowprops=dict(arrowstyle="-", lw=0.5, color="grey", shrinkA=4, shrinkB=2))
        placed.append(chosen)
        notes.append(note)
    return notes
