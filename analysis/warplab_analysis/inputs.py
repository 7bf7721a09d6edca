"""Reading the CSVs `warplab export` writes, and refusing bad ones with one sentence.

The csv module rather than pandas: every cell stays the exact string the export wrote (a
participant id such as `NA` or `'=1` is an opaque id, never a missing value or a formula),
and each record keeps the line it starts on, so an error can name the line a spreadsheet or
an editor shows, even after a quoted field that spans lines.

Every problem raises BadInput with one sentence naming the file, and the column and line
where there is one.
"""
import csv
import math
import os
import re

HITRATES = "hitrates.csv"
MATCHES = "matches.csv"
RATINGS = "ratings.csv"
SESSIONS = "sessions.csv"
MODES = "modes.csv"
CONDITIONS = "conditions.csv"
GAMES = "games.csv"

# The column that names a row's condition; exports before it was called so name it "mode",
# which the files of rows still read as (read_table's condition_column).
CONDITION = "condition"
LEGACY_CONDITION = "mode"
HITRATES_REQUIRED = ["participant", "game", CONDITION, "shots", "hits"]
MATCHES_REQUIRED = ["participant", "scored_phase", CONDITION, "green_hits", "red_hits", "misses"]
RATINGS_REQUIRED = ["statement_index", "statement"]
MODES_REQUIRED = ["mode", "description", "render_rate_hz", "added_lag_ms", "upconverts"]
CONDITIONS_REQUIRED = ["condition", "render_hz", "lag_frames", "fill", "late_warp", "view_latency_min_ms",
                       "view_latency_max_ms", "scene_latency_min_ms", "scene_latency_max_ms", "fill_hz", "refresh_hz",
                       "game", "description"]
HOLD = "hold"  # the fill that holds the last render: no frames made in between
LATE_WARPS = ("none", "rotation", "depth")
# What the rows of one condition share: everything but the refresh, the game and what follows from
# the refresh (lag in whole display frames, latencies).
SHARED_PARTS = ("render_hz", "fill", "fill_hz", "late_warp")
CONDITION_RECORD = ("condition", "description", "render_hz", "lag_frames", "added_lag_ms", "fill", "fill_hz",
                    "late_warp", "view_latency_min_ms", "view_latency_max_ms", "scene_latency_min_ms",
                    "scene_latency_max_ms", "refresh_hz", "game", "upconverts")
GAMES_REQUIRED = ["game", "hits_are", "shots_are"]
RATING_COLUMN = re.compile(r"rating_(\d+)$")
# ratings.csv's record of the protocol's ratings.min and ratings.max, on every answer.
SCALE_COLUMNS = ("scale_min", "scale_max")
# The protocol's default ratings.min and ratings.max, Yang et al.'s 1 (strongly disagree) to 7
# (strongly agree), seed 000 §8: the scale of an export from before SCALE_COLUMNS, unless
# analyze --rating-scale gives another.
DEFAULT_RATING_SCALE = (1, 7)


class BadInput(Exception):
    pass


class Table:
    """A CSV's header (on line `header_line`) and its records, each a dict with the record's first
    line in `_line`."""

    def __init__(self, path, header, records, header_line=1):
        self.path = path
        self.header = header
        self.records = records
        self.header_line = header_line


def read_table(path, required, condition_column=False):
    """condition_column: a file of rows that each name their condition, whose column an older
    export called "mode": read under its name now, CONDITION."""
    # A pipe (or a device) under a CSV's name would block the open or the read for ever.
    if os.path.exists(path) and not os.path.isfile(path):
        raise BadInput(f"{path}: is not a regular file (a pipe, socket, device or folder), not a CSV.")
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            reader = csv.reader(f, strict=True)
            header = None
            header_line = 0
            records = []
            end_of_previous = 0
            for fields in reader:
                first_line = end_of_previous + 1
                end_of_previous = reader.line_num
                if not fields:
                    continue  # a blank line
                if header is None:
                    header = [name.strip() for name in fields]
                    header_line = first_line
                    continue
                if len(fields) != len(header):
                    raise BadInput(f"{path}: line {first_line} has {len(fields)} fields but the header has "
                                   f"{len(header)}.")
                record = dict(zip(header, fields))
                record["_line"] = first_line
                records.append(record)
    except FileNotFoundError:
        raise BadInput(f"{path}: no such file.")
    except IsADirectoryError:
        raise BadInput(f"{path}: is a directory, expected a CSV file.")
    except UnicodeDecodeError:
        raise BadInput(f"{path}: is not UTF-8 text.")
    except csv.Error as e:
        raise BadInput(f"{path}: cannot be read as CSV (line {reader.line_num}: {e}).")
    except OSError as e:
        raise BadInput(f"{path}: cannot be read ({e.strerror or e}).")
    if header is None:
        raise BadInput(f"{path}: the file is empty, expected a header line with columns {', '.join(required)}.")
    if condition_column and CONDITION not in header and LEGACY_CONDITION in header:
        header = [CONDITION if name == LEGACY_CONDITION else name for name in header]
        for record in records:
            record[CONDITION] = record.pop(LEGACY_CONDITION)
    for column in required:
        if column not in header:
            raise BadInput(f"{path}: line {header_line}, the header, is missing column '{column}'.")
    return Table(path, header, records, header_line)


def text(table, record, column):
    """A non-empty string cell, kept exactly as written."""
    value = record[column]
    if value == "":
        raise BadInput(f"{table.path}: line {record['_line']}, column '{column}' is empty.")
    return value


# Counts (shots, hits, clicks, indices) above this are a corrupt or hand-made file: a session
# logs at most a few hundred thousand frames, and 1e308 "shots" would pass every other check.
# Still far above any study, so that exact integer arithmetic on huge hand-made counts (the
# tie tests use 10^17) stays possible; 10^18 also fits R's and pandas' 64-bit integers.
MAX_COUNT = 10 ** 18


def number(table, record, column, *, integer=False, optional=False):
    """A numeric cell: float (int for integer columns); None for an empty cell where allowed."""
    raw = record[column]
    where = f"{table.path}: line {record['_line']}, column '{column}'"
    if raw.strip() == "":
        if optional:
            return None
        raise BadInput(f"{where} is empty, expected a number.")
    try:
        value = int(raw) if integer else float(raw)  # int first: a count above 2^53 stays exact
    except ValueError:
        try:
            value = float(raw)
        except ValueError:
            raise BadInput(f"{where} is not a number: {raw!r}.")
    if isinstance(value, float) and not math.isfinite(value):
        raise BadInput(f"{where} is not a finite number: {raw!r}.")
    if integer:
        if isinstance(value, float) and not value.is_integer():
            raise BadInput(f"{where} is not a whole number: {raw!r}.")
        value = int(value)
        if value < 0:
            raise BadInput(f"{where} is negative: {raw!r}.")
        if value > MAX_COUNT:
            raise BadInput(f"{where} is {raw}, more than any study counts (at most {MAX_COUNT:.0e}).")
    return value


def boolean(table, record, column):
    raw = record[column].strip().lower()
    if raw in ("true", "1"):
        return True
    if raw in ("false", "0"):
        return False
    raise BadInput(f"{table.path}: line {record['_line']}, column '{column}' is not true or false: "
                   f"{record[column]!r}.")


def load_hitrates(export_dir, rows_required=True):
    """{game: {participant: {condition: (hits, shots)}}} and the number of rows, in file order.
    rows_required: a file with its header only is refused (there would be nothing to report);
    False for an export whose data is elsewhere (the discrimination game has no shots)."""
    table = read_table(os.path.join(export_dir, HITRATES), HITRATES_REQUIRED, condition_column=True)
    if not table.records and rows_required:
        raise BadInput(f"{table.path}: has a header but no data rows.")
    optional_numeric = [c for c in ("timeouts", "hit_rate") if c in table.header]
    games = {}
    first_seen = {}
    for record in table.records:
        participant = text(table, record, "participant")
        game = text(table, record, "game")
        condition = text(table, record, CONDITION)
        shots = number(table, record, "shots", integer=True)
        hits = number(table, record, "hits", integer=True)
        for column in optional_numeric:
            number(table, record, column, optional=True)
        line = record["_line"]
        if hits > shots:
            raise BadInput(f"{table.path}: line {line}, column 'hits' ({hits}) exceeds column 'shots' ({shots}).")
        key = (game, participant, condition)
        if key in first_seen:
            raise BadInput(f"{table.path}: line {line}, column 'participant': {participant!r} has a second row "
                           f"for game {game!r} and condition {condition!r} (the first is on line {first_seen[key]}).")
        first_seen[key] = line
        if shots == 0:
            continue  # a condition played without a shot or click: it ran, but has no rate to compare
        games.setdefault(game, {}).setdefault(participant, {})[condition] = (hits, shots)
    for game, participants in games.items():
        if len(participants) < 2:
            only = next(iter(participants))
            raise BadInput(f"{table.path}: column 'participant' has a single participant ({only!r}) for game "
                           f"{game!r}, which needs at least two participants for paired tests.")
    return games, len(table.records)


class RatingScale:
    """The lowest and highest answer to a statement, both included, and where they come from in
    words that follow "outside the rating scale LOW to HIGH (" in a refusal."""

    def __init__(self, low, high, source):
        self.low, self.high, self.source = low, high, source


class Scales(dict):
    """{rating column number k: RatingScale}; `default` for a k without its own."""

    def __init__(self, default):
        super().__init__()
        self.default = default

    def __missing__(self, column):
        return self.default


def rating_scales(statements, override=None):
    """The Scales of load_statements' `statements`: `override` ((low, high), from --rating-scale)
    for every statement when given; else the scale ratings.csv records for each; else (no
    ratings.csv, one without SCALE_COLUMNS, or no answer to the statement) the protocol's default."""
    if override is not None:
        return Scales(RatingScale(*override, "as --rating-scale gives it"))
    recorded = statements[4] if statements else None
    if statements is None:
        why = f"there is no {RATINGS} to record the scale"
    elif recorded is None:
        why = f"{RATINGS} has no {' and '.join(SCALE_COLUMNS)} (an export from before them)"
    else:
        why = f"{RATINGS} lists no answer to this statement to give its scale"
    scales = Scales(RatingScale(*DEFAULT_RATING_SCALE, f"the protocol's default ratings.min and ratings.max: {why}; "
                                "for a protocol with others, pass --rating-scale MIN:MAX"))
    for column, (low, high, line) in (recorded or {}).items():
        scales[column] = RatingScale(low, high, f"statement {column - 1}'s {' and '.join(SCALE_COLUMNS)} in "
                                                f"{RATINGS}, line {line}")
    return scales


def load_matches(export_dir, scales=None):
    """None without matches.csv; else (scored match records, rating columns, rows in the file, the
    `session` of every row, the table).

    A scored record: participant, condition, green_hits, red_hits, misses and `ratings`, a list with one
    value or None per rating column, in column order rating_1, rating_2, ... The columns run from
    rating_1 without a gap (rating_k answers statement k), and a scored rating_k lies on
    scales[k] (rating_scales; default: 1 to 7 for every statement).
    """
    scales = rating_scales(None) if scales is None else scales
    path = os.path.join(export_dir, MATCHES)
    if not os.path.exists(path):
        return None
    table = read_table(path, MATCHES_REQUIRED, condition_column=True)
    numbered = sorted((int(m.group(1)), name) for name in table.header if (m := RATING_COLUMN.match(name)))
    for expected, (k, name) in enumerate(numbered, start=1):
        if k != expected:
            raise BadInput(f"{path}: line {table.header_line}, the header, has column '{name}' but no column "
                           f"'rating_{expected}' (rating_k answers statement k, so the columns run from rating_1 "
                           "without a gap).")
    rating_columns = [name for _, name in numbered]
    optional_numeric = [c for c in ("clicks", "duration_s") if c in table.header]
    scored = []
    sessions = {record.get("session", "") for record in table.records}
    for record in table.records:
        if not boolean(table, record, "scored_phase"):
            continue
        match = {
            "participant": text(table, record, "participant"),
            "condition": text(table, record, CONDITION),
            "green_hits": number(table, record, "green_hits", integer=True),
            "red_hits": number(table, record, "red_hits", integer=True),
            "misses": number(table, record, "misses", integer=True),
            "ratings": [rating(table, record, name, scales[k]) for k, name in numbered],
        }
        for column in optional_numeric:
            number(table, record, column, optional=True)
        scored.append(match)
    return scored, rating_columns, len(table.records), sessions, table


def rating(table, record, column, scale):
    """A rating cell: None when empty (the session ended before it), else a number on the scale."""
    value = number(table, record, column, optional=True)
    if value is not None and not scale.low <= value <= scale.high:
        raise BadInput(f"{table.path}: line {record['_line']}, column '{column}' is {record[column].strip()}, "
                       f"outside the rating scale {scale.low} to {scale.high} ({scale.source}).")
    return value


def whole(table, record, column):
    """A whole number of either sign (a scale may start below 0)."""
    raw = record[column].strip()
    where = f"{table.path}: line {record['_line']}, column '{column}'"
    if raw == "":
        raise BadInput(f"{where} is empty, expected a whole number.")
    try:
        return int(raw)
    except ValueError:
        raise BadInput(f"{where} is not a whole number: {record[column]!r}.")


def check_rating_columns(matches, statements):
    """Every statement ratings.csv lists has its rating_k column in matches.csv: without it the
    statement's measure would silently drop out of the report."""
    if matches is None or statements is None:
        return
    table, present = matches[4], set(matches[1])
    first_lines, ratings_path = statements[2:4]
    for column, line in sorted(first_lines.items()):
        if f"rating_{column}" not in present:
            raise BadInput(f"{table.path}: line {table.header_line}, the header, has no column 'rating_{column}', "
                           f"but {ratings_path} lists statement {column - 1} (statement_index, line {line}), which "
                           f"rating_{column} answers.")


def load_statements(export_dir):
    """None without ratings.csv; else ({rating column number k+1: statement text}, notes,
    {rating column number: the line that first lists the statement}, the file's path, scales):
    scales None for an export without SCALE_COLUMNS, else {rating column number: (scale_min,
    scale_max, the line that first gives them)}, one scale per statement."""
    path = os.path.join(export_dir, RATINGS)
    if not os.path.exists(path):
        return None
    table = read_table(path, RATINGS_REQUIRED)
    present = [c for c in SCALE_COLUMNS if c in table.header]
    if len(present) == 1:
        (missing,) = set(SCALE_COLUMNS) - set(present)
        raise BadInput(f"{path}: line {table.header_line}, the header, has column '{present[0]}' but no column "
                       f"'{missing}' (the two record the protocol's rating scale together).")
    scales = {} if present else None
    texts, first_lines = {}, {}
    for record in table.records:
        index = number(table, record, "statement_index", integer=True)
        first_lines.setdefault(index + 1, record["_line"])
        if scales is not None:
            scale_of(table, record, index, scales)
        counts = texts.setdefault(index + 1, {})
        statement = record["statement"]
        counts[statement] = counts.get(statement, 0) + 1
    labels, notes = {}, []
    for column, counts in sorted(texts.items()):
        ordered = sorted(counts.items(), key=lambda item: -item[1])
        labels[column] = ordered[0][0]
        if len(ordered) > 1:
            others = "; ".join(repr(t) for t, _ in ordered[1:])
            notes.append(f"ratings.csv gives statement {column - 1} more than one text; the table uses the most "
                         f"frequent, {ordered[0][0]!r} (also seen: {others}).")
    return labels, notes, first_lines, path, scales


def scale_of(table, record, index, scales):
    """Reads a row's scale into scales (load_statements): whole numbers, min below max, and the
    same on every row of statement `index` (rating_k averages answers, so they share one scale)."""
    low, high = whole(table, record, "scale_min"), whole(table, record, "scale_max")
    where = f"{table.path}: line {record['_line']}, column"
    if low >= high:
        raise BadInput(f"{where} 'scale_min' is {low}, not below column 'scale_max' ({high}).")
    first = scales.setdefault(index + 1, (low, high, record["_line"]))
    for column, value, earlier in (("scale_min", low, first[0]), ("scale_max", high, first[1])):
        if value != earlier:
            raise BadInput(f"{where} '{column}' is {value}, but statement {index}'s {column} is {earlier} on line "
                           f"{first[2]} (the answers to one statement share one scale).")


def load_sessions(export_dir):
    """None without sessions.csv; a note string if it cannot be used; else counts of sessions."""
    path = os.path.join(export_dir, SESSIONS)
    if not os.path.exists(path):
        return None
    try:
        table = read_table(path, ["included"])
        summary = {"listed": 0, "included": 0, "by_game": {}, "players": {}}
        for record in table.records:
            included = boolean(table, record, "included")
            if included:  # by kind: "sim", "bot", "human", "replay"
                kind = record.get("player", "").split(":")[0] or "unknown"
                summary["players"][kind] = summary["players"].get(kind, 0) + 1
            game = record.get("game", "")
            per_game = summary["by_game"].setdefault(game, {"listed": 0, "included": 0})
            for counts in (summary, per_game):
                counts["listed"] += 1
                counts["included"] += int(included)
        if "game" not in table.header:
            del summary["by_game"]
        return summary
    except BadInput as e:
        return f"sessions.csv was not used: {e}"


def session_games(export_dir):
    """{session file: its game} from sessions.csv; empty without a usable one (load_sessions says why)."""
    path = os.path.join(export_dir, SESSIONS)
    if not os.path.exists(path):
        return {}
    try:
        table = read_table(path, ["file", "game"])
    except BadInput:
        return {}
    return {record["file"]: record["game"] for record in table.records if record["game"]}


def conditions_record(**parts):
    """One condition row as conditions.ConditionTable takes it; parts a file lacks stay None."""
    record = dict.fromkeys(CONDITION_RECORD)
    record.update(parts)
    return record


def load_conditions(export_dir):
    """(records, the file they come from, notes): conditions.csv's rows when it is there, else
    modes.csv's (an export from before conditions.csv) mapped into the same records, else
    (None, None, []). Records as conditions.py describes them, in file order."""
    path = os.path.join(export_dir, CONDITIONS)
    old = os.path.join(export_dir, MODES)
    if os.path.exists(path):
        notes = []
        if os.path.exists(old):
            notes.append(f"{CONDITIONS} is read and {MODES} beside it is not ({MODES} is what exports wrote before "
                         f"{CONDITIONS}; a later export into the same folder leaves it there).")
        return read_conditions(path), CONDITIONS, notes
    if os.path.exists(old):
        return read_modes_csv(old), MODES, []
    return None, None, []


def positive(table, record, column, *, optional=False):
    value = number(table, record, column, optional=optional)
    if value is not None and value <= 0:
        raise BadInput(f"{table.path}: line {record['_line']}, column '{column}' is not above 0: "
                       f"{record[column]!r}.")
    return value


def read_conditions(path):
    table = read_table(path, CONDITIONS_REQUIRED)
    records, first_of_name, first_seen = [], {}, {}
    for record in table.records:
        line = record["_line"]
        where = f"{table.path}: line {line}, column"
        name = text(table, record, "condition")
        late_warp = text(table, record, "late_warp")
        if late_warp not in LATE_WARPS:
            raise BadInput(f"{where} 'late_warp' is not {', '.join(LATE_WARPS[:-1])} or {LATE_WARPS[-1]}: "
                           f"{late_warp!r}.")
        fill = text(table, record, "fill")
        refresh_hz = positive(table, record, "refresh_hz")
        lag_frames = number(table, record, "lag_frames", integer=True)
        row = conditions_record(
            condition=name, description=record["description"], render_hz=positive(table, record, "render_hz"),
            lag_frames=lag_frames, added_lag_ms=lag_frames * 1000 / refresh_hz, fill=fill,
            fill_hz=positive(table, record, "fill_hz", optional=fill == HOLD), late_warp=late_warp,
            refresh_hz=refresh_hz, game=text(table, record, "game"),
            upconverts=fill != HOLD or late_warp != "none")
        for kind in ("view", "scene"):
            low, high = f"{kind}_latency_min_ms", f"{kind}_latency_max_ms"
            for column in (low, high):
                row[column] = number(table, record, column)
                if row[column] < 0:
                    raise BadInput(f"{where} '{column}' is negative: {record[column]!r}.")
            if row[high] < row[low]:
                raise BadInput(f"{where} '{high}' ({record[high]}) is below column '{low}' ({record[low]}).")
        key = (name, refresh_hz, row["game"])
        if key in first_seen:
            raise BadInput(f"{where} 'condition': {name!r} has a second row for refresh_hz {record['refresh_hz']} "
                           f"and game {row['game']!r} (the first is on line {first_seen[key]}).")
        first_seen[key] = line
        # The parts are the condition; only what follows from the display refresh may differ.
        if name in first_of_name:
            earlier, earlier_record = first_of_name[name]
            for column in SHARED_PARTS:
                if row[column] != earlier[column]:
                    raise BadInput(f"{where} '{column}': {name!r} has {record[column]!r} here but "
                                   f"{earlier_record[column]!r} on line {earlier_record['_line']} (the rows of one "
                                   "condition differ only in refresh_hz, game, lag_frames and the latencies).")
        else:
            first_of_name[name] = (row, record)
        records.append(row)
    return records


def read_modes_csv(path):
    """modes.csv's rows as condition records: its upconverts column as written, what fills the
    frames between renders from its method (or upconversion kind), and no late warp (warplab
    had none when it wrote modes.csv)."""
    table = read_table(path, MODES_REQUIRED)
    rows, first_seen = [], {}
    for record in table.records:
        name = text(table, record, "mode")
        if name in first_seen:
            raise BadInput(f"{table.path}: line {record['_line']}, column 'mode': {name!r} has a second row (the first "
                           f"is on line {first_seen[name]}).")
        first_seen[name] = record["_line"]
        upconverts = boolean(table, record, "upconverts")
        fill = HOLD
        if upconverts:
            fill = record.get("method") or record.get("upconversion") or None
        fill_hz = None
        if "upconverted_rate_hz" in record:
            fill_hz = number(table, record, "upconverted_rate_hz", optional=True)
        rows.append(conditions_record(
            condition=name, description=record["description"], render_hz=number(table, record, "render_rate_hz"),
            added_lag_ms=number(table, record, "added_lag_ms"), fill=fill, fill_hz=fill_hz, late_warp="none",
            upconverts=upconverts))
    return rows


def load_games(export_dir):
    """{} without games.csv; else {game: {"hits_are", "shots_are", "tables"}} in file order: what
    each game's hits and shots in hitrates.csv count, in words, and the game's own tables (a list of
    file names; None for an export from before games.csv listed them)."""
    path = os.path.join(export_dir, GAMES)
    if not os.path.exists(path):
        return {}
    table = read_table(path, GAMES_REQUIRED)
    games = {}
    for record in table.records:
        games[text(table, record, "game")] = {"hits_are": text(table, record, "hits_are"),
                                              "shots_are": text(table, record, "shots_are"),
                                              # Empty for a game without tables of its own.
                                              "tables": ([t for t in record["tables"].split(";") if t]
                                                         if "tables" in table.header else None)}
    return games


ANSWERS = "answers.csv"
ANSWERS_REQUIRED = ["participant", "kind", "question_index", "prompt", CONDITION, "value", "text"]
ANSWER_KINDS = ("likert", "choice", "text")
# player_kind, as export writes it (session::playerKind): who played a session.
PEOPLE = "human"
SCRIPTED = ("bot", "simulated")


def load_player_kinds(export_dir):
    """None for an export without hitrates.csv's player_kind column (from before it); else
    {participant: the set of kinds of their sessions} over hitrates.csv's rows (a cell may list
    several, `;`-separated, for an id that named a person in one session and a bot in another)."""
    table = read_table(os.path.join(export_dir, HITRATES), HITRATES_REQUIRED, condition_column=True)
    if "player_kind" not in table.header:
        return None
    kinds = {}
    for record in table.records:
        cell = record["player_kind"]
        kinds.setdefault(record["participant"], set()).update(k for k in cell.split(";") if k)
    return kinds


def load_answers(export_dir):
    """None without answers.csv; else its answers of the scored blocks in file order, each a dict:
    participant, kind, question (index), question_id, prompt, condition, value (None for text),
    text, block (block_index or None), player_kind (None in an export from before it)."""
    path = os.path.join(export_dir, ANSWERS)
    if not os.path.exists(path):
        return None
    table = read_table(path, ANSWERS_REQUIRED, condition_column=True)
    answers = []
    for record in table.records:
        if "scored_phase" in table.header and not boolean(table, record, "scored_phase"):
            continue
        kind = text(table, record, "kind")
        if kind not in ANSWER_KINDS:
            raise BadInput(f"{path}: line {record['_line']}, column 'kind' is not likert, choice or text: {kind!r}.")
        value = None
        if kind != "text":
            value = number(table, record, "value")
            if not float(value).is_integer():
                raise BadInput(f"{path}: line {record['_line']}, column 'value' is not a whole number: "
                               f"{record['value']!r}.")
            value = int(value)
            if kind == "likert":
                answer_on_scale(table, record, value)
        block = None
        if "block_index" in table.header and record["block_index"].strip() != "":
            block = whole(table, record, "block_index")
        answers.append({"participant": text(table, record, "participant"), "kind": kind,
                        "question": number(table, record, "question_index", integer=True),
                        "question_id": record.get("question_id", ""), "prompt": record["prompt"],
                        "condition": record[CONDITION], "value": value, "text": record["text"], "block": block,
                        "player_kind": record.get("player_kind")})
    return answers


def answer_on_scale(table, record, value):
    """A Likert answer within the scale its row records (scale_min, scale_max; an export from before
    them records none): an answer outside would move every summary and model of its question."""
    if not all(c in table.header and record[c].strip() != "" for c in SCALE_COLUMNS):
        return
    low, high = whole(table, record, "scale_min"), whole(table, record, "scale_max")
    if not low <= value <= high:
        raise BadInput(f"{table.path}: line {record['_line']}, column 'value' is {value}, outside the question's "
                       f"scale {low} to {high} (its scale_min and scale_max).")


FRAME_TIMES = "frametimes.csv"


def load_frame_times(export_dir):
    """{(game, condition, refresh_hz): ([time_s], [frame_time_ms])} from frametimes.csv (docs/export.md),
    in file order; {} for an export from before it."""
    path = os.path.join(export_dir, FRAME_TIMES)
    if not os.path.exists(path):
        return {}
    table = read_table(path, ["game", "condition", "refresh_hz", "time_s", "frame_time_ms"])
    series = {}
    for record in table.records:
        key = (text(table, record, "game"), text(table, record, "condition"),
               positive(table, record, "refresh_hz"))
        times, frame_times = series.setdefault(key, ([], []))
        times.append(number(table, record, "time_s"))
        frame_times.append(positive(table, record, "frame_time_ms"))
    return series



LATENCY = "latency.csv"
LATENCY_KINDS = ("view", "scene")
# Weights are shares written as shortest round-trip decimals: their sum is 1 but for rounding.
WEIGHT_SUM_SLACK = 1e-6


def load_latency(export_dir):
    """{(game, condition, refresh_hz): {kind: [(latency_ms_from, latency_ms_to, weight)]}} from
    latency.csv (docs/export.md), kinds and spans in file order; {} for an export from before it.
    Each kind's weights must add up to 1: a histogram drawn from fewer spans would be wrong, not
    partial."""
    path = os.path.join(export_dir, LATENCY)
    if not os.path.exists(path):
        return {}
    table = read_table(path, ["game", "condition", "refresh_hz", "kind", "latency_ms_from", "latency_ms_to",
                              "weight"])
    distributions = {}
    for record in table.records:
        key = (text(table, record, "game"), text(table, record, "condition"),
               positive(table, record, "refresh_hz"))
        kind = text(table, record, "kind")
        if kind not in LATENCY_KINDS:
            raise BadInput(f"{path}: line {record['_line']}, column 'kind' is not view or scene: {kind!r}.")
        low = number(table, record, "latency_ms_from")
        high = number(table, record, "latency_ms_to")
        if high <= low:
            raise BadInput(f"{path}: line {record['_line']}, column 'latency_ms_to' is not above latency_ms_from: "
                           f"{record['latency_ms_to']!r}.")
        spans = distributions.setdefault(key, {}).setdefault(kind, [])
        spans.append((low, high, positive(table, record, "weight")))
    for (game, condition, refresh), kinds in distributions.items():
        for kind, spans in kinds.items():
            total = sum(weight for _, _, weight in spans)
            if abs(total - 1.0) > WEIGHT_SUM_SLACK:
                raise BadInput(f"{path}: the weights of {condition}'s {kind} latency ({game}, {refresh:g} Hz) add "
                               f"up to {total:.9g}, not 1.")
    return distributions
