"""Markdown cells, numbers and tables as report.md writes them, shared by its sections."""
import math

NOTHING = "–"


def cell(text):
    """Markdown table cell: characters that would start a table column, emphasis or a link escaped."""
    out = str(text).replace("\r", " ").replace("\n", " ")
    for ch in "\\`*_[]<>|":
        out = out.replace(ch, "\\" + ch)
    return out


def fmt(value, spec):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return NOTHING if value is None or math.isnan(value) else ("∞" if value > 0 else "−∞")
    return format(value, spec)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines) + "\n"
