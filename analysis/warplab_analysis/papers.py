"""The papers' people: the human results warplab's two studies re-create, as published, for setting
beside a study's own (report.papers_section) and for fitting the simulated participants
(analysis/fit_participants.py). Figures copied from the sources in shared/seeds; nothing here is
computed from warplab's data.
"""
import statistics

# Pulkkinen 2015 (seed 004), Table 1: hits out of 225 targets per condition, per participant
# (20 people): conventional 120 Hz, 15-to-120 Hz warp, conventional 15 Hz.
THESIS_TARGETS = 225
THESIS_HITS = [
    (170, 140, 112), (173, 152, 119), (161, 144, 106), (127, 104, 94), (128, 106, 75),
    (152, 123, 102), (169, 133, 105), (147, 123, 108), (122, 107, 86), (104, 82, 61),
    (168, 128, 114), (173, 156, 137), (91, 69, 53), (148, 130, 89), (171, 161, 134),
    (137, 107, 108), (185, 166, 122), (139, 119, 94), (170, 141, 122), (185, 162, 161),
]
THESIS_CONDITIONS = ("conv120", "warp15to120", "conv15")
THESIS_BEST = "conv120"


def thesis_hit_rates():
    """condition -> (mean hit rate over the 20 people, SD across them)."""
    out = {}
    for i, condition in enumerate(THESIS_CONDITIONS):
        rates = [row[i] / THESIS_TARGETS for row in THESIS_HITS]
        out[condition] = (statistics.mean(rates), statistics.stdev(rates))
    return out


# Yang et al. 2011 (seed 000), Table 2: mean and SD across 33 people of each measure per condition
# (green, red hits and misses per 45 s match; ratings on 1..7 of the four statements).
YANG_BEST = "conv60"
YANG_CONDITIONS = ("conv60", "conv30", "conv15", "lag50", "lag100", "lag200", "bireproj15to60")
YANG_TABLE2 = {
    # measure: {condition: (M, SD)}
    "green_hits": {"bireproj15to60": (31.64, 7.37), "conv60": (43.79, 11.07), "conv30": (41.65, 9.86),
                   "conv15": (31.89, 6.82), "lag50": (35.47, 7.24), "lag100": (29.85, 6.98),
                   "lag200": (24.24, 5.72)},
    "red_hits": {"bireproj15to60": (3.44, 2.91), "conv60": (1.92, 1.53), "conv30": (2.20, 1.76),
                 "conv15": (3.32, 1.75), "lag50": (3.11, 2.84), "lag100": (4.33, 2.78), "lag200": (6.68, 3.55)},
    "misses": {"bireproj15to60": (22.01, 1.45), "conv60": (15.68, 8.34), "conv30": (19.32, 9.40),
               "conv15": (25.42, 12.63), "lag50": (20.38, 10.74), "lag100": (25.11, 13.73),
               "lag200": (31.59, 17.16)},
    "enjoyed": {"bireproj15to60": (4.38, 1.14), "conv60": (5.42, 1.15), "conv30": (4.65, 1.07),
                "conv15": (2.61, 1.18), "lag50": (4.47, 1.08), "lag100": (3.77, 1.01), "lag200": (2.88, .977)},
    "difficult": {"bireproj15to60": (4.26, 1.01), "conv60": (3.24, 1.29), "conv30": (3.85, 1.09),
                  "conv15": (4.80, 1.27), "lag50": (4.00, 1.05), "lag100": (4.58, 1.17), "lag200": (5.00, 1.05)},
    "responsive": {"bireproj15to60": (4.03, 1.09), "conv60": (5.74, 1.08), "conv30": (5.18, .98),
                   "conv15": (3.71, 1.25), "lag50": (4.59, 1.07), "lag100": (3.68, 1.27), "lag200": (2.45, 1.19)},
    "smooth": {"bireproj15to60": (5.36, 1.22), "conv60": (5.67, 1.24), "conv30": (3.71, 1.25),
               "conv15": (1.80, .90), "lag50": (5.38, 1.21), "lag100": (5.06, 1.31), "lag200": (4.83, 1.19)},
}
# Which word of a rating statement names which of Yang's four (the statements as published).
YANG_STATEMENT_WORDS = {"enjoy": "enjoyed", "difficult": "difficult", "responsive": "responsive",
                        "smooth": "smooth"}


def yang_ratio(measure="green_hits"):
    """condition -> the measure's mean relative to 60 fps's."""
    table = YANG_TABLE2[measure]
    return {condition: table[condition][0] / table[YANG_BEST][0] for condition in YANG_CONDITIONS}


def yang_rating_key(statement):
    """The Yang measure a rating statement's text names, or None."""
    text = statement.lower()
    for word, key in YANG_STATEMENT_WORDS.items():
        if word in text:
            return key
    return None
