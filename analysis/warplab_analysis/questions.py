"""The questions asked after blocks (answers.csv), summarised per question and condition:
Likert answers by median, quartiles and IQR (R's default quantiles, type 7, numpy's "linear"), over
every answer in the condition (a participant who answered twice there counts twice); choices by
how often each option was chosen; text answers listed by participant and block.
"""
import numpy as np

MIXED = ""  # answers.csv's condition for a block whose trials mixed conditions


def likert_summary(values):
    q25, median, q75 = (float(v) for v in np.percentile(np.asarray(values, dtype=float), [25, 50, 75]))
    return {"n": len(values), "median": median, "q25": q25, "q75": q75, "iqr": q75 - q25}


def summarise(answers, condition_order, order_key):
    """One entry per question (by its place in the protocol and its prompt), in protocol order:
    {question, question_id, prompt, kind, conditions: [...], by_condition: {condition: summary}}; a Likert
    summary likert_summary's, a choice's {n, counts: [{option, text, count}]} by option number, a
    text question's {n, answers: [{participant, block, text}]} by participant then block."""
    questions = {}
    for a in answers:
        key = (a["question"], a["prompt"], a["kind"])
        q = questions.setdefault(key, {"question": a["question"], "question_id": a["question_id"],
                                       "prompt": a["prompt"], "kind": a["kind"], "answers": {}})
        q["answers"].setdefault(a["condition"], []).append(a)
    out = []
    for key in sorted(questions, key=lambda k: (k[0], k[1], k[2])):
        q = questions.pop(key)
        given = q.pop("answers")
        conditions = ([c for c in condition_order if c in given]
                      + sorted(c for c in given if c not in condition_order))
        by_condition = {}
        for condition in conditions:
            rows = given[condition]
            if q["kind"] == "likert":
                by_condition[condition] = likert_summary([r["value"] for r in rows])
            elif q["kind"] == "choice":
                counts = {}
                for r in rows:
                    counts.setdefault(r["value"], [r["text"], 0])[1] += 1
                by_condition[condition] = {"n": len(rows), "counts": [{"option": v, "text": t, "count": c}
                                                                      for v, (t, c) in sorted(counts.items())]}
            else:
                listed = sorted(rows, key=lambda r: (order_key(r["participant"]),
                                                     -1 if r["block"] is None else r["block"]))
                by_condition[condition] = {"n": len(rows), "answers": [{"participant": r["participant"],
                                                                        "block": r["block"], "text": r["text"]}
                                                                       for r in listed]}
        q.update(conditions=conditions, by_condition=by_condition)
        out.append(q)
    return out
