"""The questions asked after blocks (answers.csv), summarised per question and condition:
Likert answers by median, quartiles and IQR (R's default quantiles, type 7, numpy's "linear"), over
every answer in the condition (a participant who answered twice there counts twice); choices by
how often each option was chosen; text answers listed by participant and block.
"""
import numpy as np

MIXED = ""  # answers.csv's mode for a block whose trials mixed conditions


def likert_summary(values):
    q25, median, q75 = (float(v) for v in np.percentile(np.asarray(values, dtype=float), [25, 50, 75]))
    return {"n": len(values), "median": median, "q25": q25, "q75": q75, "iqr": q75 - q25}


def summarise(answers, mode_order, order_key):
    """One entry per question (by its place in the protocol and its prompt), in protocol order:
    {question, question_id, prompt, kind, modes: [...], by_mode: {mode: summary}}; a Likert
    summary likert_summary's, a choice's {n, counts: [{option, text, count}]} by option number, a
    text question's {n, answers: [{participant, block, text}]} by participant then block."""
    questions = {}
    for a in answers:
        key = (a["question"], a["prompt"], a["kind"])
        q = questions.setdefault(key, {"question": a["question"], "question_id": a["question_id"],
                                       "prompt": a["prompt"], "kind": a["kind"], "answers": {}})
        q["answers"].setdefault(a["mode"], []).append(a)
    out = []
    for key in sorted(questions, key=lambda k: (k[0], k[1], k[2])):
        q = questions.pop(key)
        given = q.pop("answers")
        modes = [m for m in mode_order if m in given] + sorted(m for m in given if m not in mode_order)
        by_mode = {}
        for mode in modes:
            rows = given[mode]
            if q["kind"] == "likert":
                by_mode[mode] = likert_summary([r["value"] for r in rows])
            elif q["kind"] == "choice":
                counts = {}
                for r in rows:
                    counts.setdefault(r["value"], [r["text"], 0])[1] += 1
                by_mode[mode] = {"n": len(rows), "counts": [{"option": v, "text": t, "count": c}
                                                            for v, (t, c) in sorted(counts.items())]}
            else:
                listed = sorted(rows, key=lambda r: (order_key(r["participant"]),
                                                     -1 if r["block"] is None else r["block"]))
                by_mode[mode] = {"n": len(rows), "answers": [{"participant": r["participant"], "block": r["block"],
                                                              "text": r["text"]} for r in listed]}
        q.update(modes=modes, by_mode=by_mode)
        out.append(q)
    return out
