"""report.md's first analysis: the trial-level mixed models that R fitted (mixed_models.py,
analysis/r/mixed_models.R), a subsection per game and measure, before the papers' own analyses.
Estimates have 3 significant digits (probabilities 3 decimals), p values 4; report.json and
mixed_models.json have them all.
"""
from . import players
from .markdown import NOTHING, cell, fmt, table

SCALE_FORMATS = {"probability": ".3f", "count": ".2f", "mean answer": ".2f"}
LINK_SCALES = {"binomial": "logit", "poisson": "log", "negbin": "log", "clmm": "latent logit"}
# What a ratio says, per engine, in the words under its table.
RATIO_WORDS = {
    "binomial": "the odds of a hit in a over those in b",
    "poisson": "the expected count in a over that in b",
    "negbin": "the expected count in a over that in b",
    "clmm": "the odds of an answer above any given level in a over those in b",
}


def intro(out, section):
    packages = section.get("packages") or {}
    versions = ", ".join(f"{name} {version}" for name, version in packages.items())
    out.append(
        "Each game's primary measures modelled trial by trial, condition as the fixed effect and participant as "
        "the random factor: hits by logit mixed models rather than ANOVAs of proportions (Jaeger 2008), counts "
        "per match by Poisson models (negative binomial where the Poisson fit is overdispersed: Pearson χ² "
        "against its residual df, p < 0.05; Bolker et al. 2009), Likert answers by cumulative-link mixed models "
        "(ordinal::clmm, a random intercept per participant). The random effects start maximal for the design, a "
        "correlated random slope of condition per participant (Barr et al. 2013), and step down only when a fit "
        "is singular (lme4::isSingular) or does not converge: first to uncorrelated random effects (numeric "
        "dummy columns, as afex does: lme4's `||` keeps a factor's correlations), then to a random intercept "
        "(Matuschek et al. 2017). Each condition's estimated marginal mean on the response scale with its 95 % CI, "
        "and every pair of conditions a / b (a first in the condition order) as a ratio with its 95 % CI, "
        "unadjusted, and a Holm-adjusted p over the model's pairs, by emmeans; the reference level is the "
        "report's reference condition where the game has one, else the first in the condition order."
        + (f" Fitted by R {section['r_version']} ({versions})." if section.get("r_version") else "") + "\n")
    out.append(f"The script that fitted them is `{section['script']}` beside this report: `Rscript "
               f"{section['script']} [EXPORT_DIR]` prints these estimates again and writes `{section['results']}` "
               f"and `{section['models_file']}`, the fitted models the sample-size plan below simulates from "
               "(docs/export.md, \"Mixed models\"). Each paper's own analysis follows it, replicated on this study's "
               "data and labelled "
               "so: sign tests of per-participant hit rates (Pulkkinen 2014), paired t, Wilcoxon and repeated-measures "
               "ANOVA of per-participant averages (Yang et al. 2011).\n")


def section(out, results, level=2):
    """The mixed models' section (report.json's `mixed_models`)."""
    mm = results.get("mixed_models")
    if mm is None:
        return
    h = "#" * level
    out.append(f"{h} Mixed models, trial by trial\n")
    if mm["left_out"]:
        out.append(f"{mm['left_out']}\n")  # our sentence, its code in backticks
        return
    intro(out, mm)
    who = results["players"]
    if who["analysed"] is not None and len(who["groups"]) > 1:
        out.append(f"Fitted to the {cell(players.GROUP_LABELS[who['analysed']])} only, as the statistics below; "
                   "the other groups are not modelled.\n")
    for note in mm["notes"]:
        out.append(f"{cell(note)}\n")
    for model in mm["models"]:
        model_section(out, model, level + 1)
    for kind, words in (("contrasts", "every pair of conditions as a ratio with its 95 % CI"),
                        ("means", "each condition's estimated mean with its 95 % CI beside each participant's own")):
        if kind in mm["figures"]:
            out.append(f"![Mixed models: {words}]({mm['figures'][kind]})\n")


def title(model):
    game = model["game"]
    return f"{game[:1].upper()}{game[1:]}: {model['label']} ({model['source']})"


def model_section(out, model, level):
    out.append(f"{'#' * level} {cell(title(model))}\n")
    if not model["fitted"]:
        steps(out, model)
        for note in model["notes"]:
            out.append(f"{cell(note)}\n")
        return
    out.append(f"`{model['call_text']}`: {model['n_observations']} {cell(model['unit'])} of "
               f"{model['n_participants']} participants; reference level {cell(model['reference'])}.\n")
    if model.get("dispersion"):
        dispersion(out, model)
    steps(out, model)
    scale = model["means_scale"]
    spec = SCALE_FORMATS.get(scale, ".3g")
    rows = [[cell(e["condition"]), interval(e["estimate"], e["low"], e["high"], spec)] for e in model["means"]]
    out.append(table(["condition", f"estimated {scale} [95 % CI]"], rows))
    if model["engine"] == "clmm":
        out.append("The mean answer is emmeans' mean.class, the expected class under the model, on the question's "
                   "own values when the answers given are consecutive whole numbers (else class 1 is the lowest "
                   "answer given).\n")
    if model["contrasts"]:
        rows = [[f"{cell(c['a'])} / {cell(c['b'])}", interval(c["ratio"], c["low"], c["high"], ".3g"),
                 fmt(c["z"], ".2f"), fmt(c["p_holm"], ".4g")] for c in model["contrasts"]]
        out.append(table(["a / b", f"{model['ratio']} [95 % CI, unadjusted]", "z", "p (Holm)"], rows))
        article = "An" if model["ratio"][0] in "aeiou" else "A"
        out.append(f"{article} {model['ratio']} is {RATIO_WORDS[model['engine']]}.\n")
    random_effects(out, model)
    for note in model["notes"]:
        out.append(f"{cell(note)}\n")


def interval(value, low, high, spec):
    if value is None:
        return NOTHING
    return f"{fmt(value, spec)} [{fmt(low, spec)}, {fmt(high, spec)}]"


def dispersion(out, model):
    d = model["dispersion"]
    verdict = ("overdispersed, so the counts are modelled by a negative binomial GLMM (lme4::glmer.nb, θ = "
               f"{fmt(model.get('theta'), '.3g')})" if model["engine"] == "negbin" else
               "overdispersed, but the negative binomial model could not be fitted: the Poisson model is kept"
               if d["overdispersed"] else "not overdispersed, so the Poisson model is kept")
    out.append(f"Poisson dispersion: Pearson χ² = {fmt(d['pearson_chisq'], '.4g')} on {fmt(d['df'], 'g')} residual "
               f"df (ratio {fmt(d['ratio'], '.3g')}, p = {fmt(d['p'], '.4g')}): {verdict}.\n")


def steps(out, model):
    """Which random-effects structure was kept, and why each richer one was dropped: for counts that
    went negative binomial, the Poisson ladder first, then the negative binomial's from its step."""
    if model.get("poisson_attempts"):
        ladders = [(" (Poisson)", model["poisson_attempts"]), (" (negative binomial)", model.get("attempts") or [])]
    else:
        ladders = [("", model.get("attempts") or [])]
    words = []
    for k, (family, attempts) in enumerate(ladders):
        dropped = [a for a in attempts if not a["kept"]]
        for a in dropped:
            words.append(f"The {a['step']} model{family}, `{a['formula']}`, was dropped: "
                         f"{cell('; '.join(a['problems']) or 'it could not be fitted')}.")
        kept = [a for a in attempts if a["kept"]]
        if not kept:
            continue
        a = kept[-1]
        if k < len(ladders) - 1:
            words.append(f"The Poisson ladder stopped at the {a['step']} model, where the negative binomial's began.")
        elif a["problems"]:
            words.append(f"The {a['step']} model{family} is kept, the last step, although "
                         f"{cell('; '.join(a['problems']))}.")
        else:
            words.append(f"The {a['step']} model{family} " + ("is kept." if dropped else
                                                              "fitted without problems and is kept."))
    if words:
        out.append(" ".join(words) + "\n")


def random_effects(out, model):
    effects = model["random_effects"]
    scale = LINK_SCALES[model["engine"]]
    sds = "; ".join(f"{cell(r['term'])} {fmt(r['sd'], '.3g')}" for r in effects["sds"])
    line = f"Random effects, participant SDs on the {scale} scale: {sds}."
    if effects["correlations"]:
        line += " Correlations: " + "; ".join(f"{cell(r['a'])} with {cell(r['b'])} {fmt(r['correlation'], '.2f')}"
                                              for r in effects["correlations"]) + "."
    out.append(line + "\n")
