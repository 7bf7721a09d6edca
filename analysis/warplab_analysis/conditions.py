"""What the export's condition table says about each condition, and the order in which the report
compares them.

A condition is what the other files' `condition` columns name (`mode` in an older export). A lab
composes its own in the protocol (render rate, added latency in display frames, what fills the
frames between renders, late warp: re-projecting an old lagged frame to the display instant's
camera, Kim et al. 2020), so the analysis keeps no list of conditions of its own: it learns them
from conditions.csv, or from modes.csv in an export from before conditions.csv, whose rows
inputs.load_conditions maps into the same records. A record:

    condition, description, render_hz, lag_frames, added_lag_ms, fill, fill_hz, late_warp,
    view_latency_min_ms, view_latency_max_ms, scene_latency_min_ms, scene_latency_max_ms,
    refresh_hz, game, upconverts

with None where the file does not say (modes.csv has no refresh, game or latencies). A name has
one record per display refresh and game it ran at; inputs.load_conditions has checked that the
records of one name agree in everything but the refresh, the game, lag_frames, added_lag_ms and
the latencies, which follow from the refresh.
"""


class ConditionTable:
    """The order puts the conditions that upconvert first (in the table's order), so a sign test's
    a − b is upconversion minus the other condition, as Pulkkinen's thesis reports warp against
    conventional rendering; then the others from the least added lag (ms) and, at equal lag, the
    highest render rate (conv120 before conv15 before lag50); the table's order breaks ties.
    Conditions the table does not list come last, by name.

    records: the table's rows in file order; None without a table, when every condition is unknown.
    """

    def __init__(self, records):
        self.records = list(records or [])
        self.rows = {}
        for record in self.records:
            self.rows.setdefault(record["condition"], []).append(record)
        self.index = {name: k for k, name in enumerate(self.rows)}

    def known(self, name):
        return name in self.rows

    def first(self, name):
        """The name's first row: its parts (the rows agree on them) and its description."""
        return self.rows[name][0]

    def upconverts(self, name):
        return name in self.rows and self.first(name)["upconverts"]

    def description(self, name):
        return self.first(name)["description"] if name in self.rows else None

    def added_lag_ms(self, name):
        """The least over the name's rows: at another refresh a lag of whole display frames may
        round to a slightly different time, and the order needs one number."""
        return min(r["added_lag_ms"] for r in self.rows[name])

    def conventional_rate(self, name):
        """The render rate of a condition that neither upconverts nor adds lag (conv120: 120); else None."""
        if name not in self.rows or self.upconverts(name) or self.added_lag_ms(name) != 0:
            return None
        return self.first(name)["render_hz"]

    def order(self, names):
        def key(name):
            if self.upconverts(name):
                return 0, 0.0, 0.0, self.index[name]
            return 1, self.added_lag_ms(name), -self.first(name)["render_hz"], self.index[name]
        known = sorted((n for n in set(names) if n in self.rows), key=key)
        return known + sorted(n for n in set(names) if n not in self.rows)

    def all_conditions(self):
        """Every condition the table lists, in the comparison order: what gives each one its colour."""
        return self.order(self.rows)

    def rows_for(self, name, game=None):
        """The name's rows, those of `game` when it has any there (else all of them)."""
        rows = self.rows.get(name, [])
        of_game = [r for r in rows if game is not None and r["game"] == game]
        return of_game or rows

    def latency(self, name, game=None):
        """(view min, view max, scene min, scene max) in ms over the name's rows for `game`; None
        when the table has no latencies for it (modes.csv)."""
        rows = [r for r in self.rows_for(name, game) if r["view_latency_min_ms"] is not None]
        if not rows:
            return None
        return (min(r["view_latency_min_ms"] for r in rows), max(r["view_latency_max_ms"] for r in rows),
                min(r["scene_latency_min_ms"] for r in rows), max(r["scene_latency_max_ms"] for r in rows))

