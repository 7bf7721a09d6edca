"""Who played: people apart from scripted players.

export's player_kind (hitrates.csv, from each session's `player`) says per participant whether a
person played (`human`), a scripted player (`bot`, `simulated`), another session's input
(`replay`), or a kind this analysis does not know. A pilot that mixes people and bots must not put
both into one sign test without a word, so the report analyses each group on its own unless asked
to pool them (analyze --pool-players), and says at its top who is who.
"""
from . import inputs

PEOPLE, SCRIPTED, OTHER = "people", "scripted", "other"
GROUP_ORDER = (PEOPLE, SCRIPTED, OTHER)
GROUP_LABELS = {PEOPLE: "people", SCRIPTED: "scripted players (bots and simulated participants)",
                OTHER: "other players (replays, unknown kinds, or one id with sessions of several kinds)"}
UNKNOWN_NOTE = ("hitrates.csv has no player_kind column (an export from before it): whether people or scripted "
                "players played is unknown, and every participant is analysed together.")
# How the report's first line counts each kind: (one, several).
KIND_NOUNS = {"human": ("person", "people"), "bot": ("bot", "bots"),
              "simulated": ("simulated participant", "simulated participants"), "replay": ("replay", "replays")}


def group_of(kinds):
    """The group of a participant whose sessions were played by `kinds` (a set)."""
    if kinds == {inputs.PEOPLE}:
        return PEOPLE
    if kinds and kinds <= set(inputs.SCRIPTED):
        return SCRIPTED
    return OTHER


def kind_of(kinds):
    """One word for a participant's kinds: the kind, "unknown", or "mixed"."""
    if not kinds:
        return "unknown"
    return next(iter(kinds)) if len(kinds) == 1 else "mixed"


def groups(kinds, participants, order_key):
    """{group: [participants]} in GROUP_ORDER, each list in `order_key` order; groups without
    participants left out. kinds None (an export without player_kind): everyone in OTHER."""
    out = {}
    for p in participants:
        group = OTHER if kinds is None else group_of(kinds.get(p, set()))
        out.setdefault(group, []).append(p)
    return {g: sorted(out[g], key=order_key) for g in GROUP_ORDER if g in out}


def sentence(kinds, participants, order_key):
    """"4 participants: 2 people (P1, P2), 2 bots (P3, P4)."; None without player kinds."""
    if kinds is None:
        return None
    by_kind = {}
    for p in sorted(participants, key=order_key):
        by_kind.setdefault(kind_of(kinds.get(p, set())), []).append(p)
    parts = []
    for kind in list(KIND_NOUNS) + ["mixed", "unknown"]:
        who = by_kind.get(kind)
        if not who:
            continue
        one, several = KIND_NOUNS.get(kind, (f"{kind} player", f"{kind} players"))
        if kind == "mixed":
            one, several = "id with sessions of several kinds", "ids with sessions of several kinds"
        elif kind == "unknown":
            one, several = "player of unknown kind", "players of unknown kind"
        parts.append(f"{len(who)} {one if len(who) == 1 else several} ({', '.join(who)})")
    n = len(participants)
    return f"{n} participant{'' if n == 1 else 's'}: {', '.join(parts)}."
