# mixed_models.R -- trial-level mixed models of a warplab export (docs/export.md, "Mixed models").
#
#   Rscript mixed_models.R [EXPORT_DIR [OUT_DIR]]
#
# EXPORT_DIR: the folder `warplab export` wrote (default: SETTINGS$export_dir below, the export
# the report was made from). OUT_DIR: where mixed_models.json and mixed_models.rds go (default:
# the folder this script is in). It prints every estimate, and writes the same numbers to
# mixed_models.json, which `analysis/analyze` reads into report.md and report.json.
#
# Per game and primary measure, one model, condition the fixed effect, participant the random
# factor (Jaeger 2008: logit mixed models, not ANOVAs of proportions; Barr et al. 2013: the
# maximal random effects the design justifies, stepped down as models.R says):
#   - every game's trials (shots.csv, scored_phase true): hit ~ condition, binomial logit --
#     the shooter's hit per target (a timeout is a miss), the click game's green hit per click;
#   - the click game's matches (matches.csv, scored): green_hits ~ condition, Poisson, or negative
#     binomial (lme4::glmer.nb) where the Poisson fit is overdispersed;
#   - each Likert question (answers.csv, kind likert, per game and question):
#     answer ~ condition + (1 | participant), cumulative logit (ordinal::clmm).
# Then, by emmeans: the estimated marginal mean of each condition on the response scale with its
# 95 % CI, and every pair of conditions as a ratio (odds, rate, cumulative odds) with an
# unadjusted 95 % CI and a Holm-adjusted p.
#
# mixed_models.rds -- readRDS() gives a named list, one element per fitted model, named
# "GAME/MEASURE": "shooter/hit", "click/hit", "click/green_hits", "click/likert:ID" (ID the
# question's id, or q and its index when it has none). Each element is a list:
#   model      the fitted object: an lme4 merMod (glmerMod; glmer.nb's is one too) or an
#              ordinal clmm
#   formula    the formula kept after stepping down (text: read it with as.formula())
#   engine     "binomial", "poisson", "negbin" or "clmm"
#   step       "maximal", "uncorrelated" or "random intercept"
#   reference  the reference condition: the first level of data$condition
#   data       the data frame it was fitted to: participant (factor), condition (factor, the
#              reference first), the response (hit 0/1, green_hits, or answer as an ordered
#              factor) and d_2, d_3, ... (numeric dummies of levels 2, 3, ..., which the
#              uncorrelated step's formula uses)
#   dummies    c(d_2 = "level 2's name", ...)
#   game, measure, label   what was modelled, in words
# simulate(x$model) or lme4::refit(x$model, newresponse) start a power simulation from it.

# >>> settings: analyze writes the values it used for the report in the copy beside it
SETTINGS <- list(
  export_dir = "export",        # EXPORT_DIR when none is given
  condition_order = NULL,       # the report's condition order; NULL: conditions by name
  reference = list(),           # game -> the report's reference condition (else the first in order)
  participants = NULL,          # the participants the report analyses; NULL: everyone
  matches_game = NULL           # the game whose matches matches.csv holds; NULL: "matches"
)
# <<< settings

script_path <- function() {
  file <- sub("^--file=", "", grep("^--file=", commandArgs(FALSE), value = TRUE))
  if (length(file) == 1) normalizePath(file) else file.path(getwd(), "mixed_models.R")
}

source(file.path(dirname(script_path()), "models.R"))  # analyze's copy has models.R here, inline

# Debian's packages for R's: the one sentence a report gives when R lacks one.
DEBIAN <- c(lme4 = "r-cran-lme4", emmeans = "r-cran-emmeans", ordinal = "r-cran-ordinal",
            jsonlite = "r-cran-jsonlite")
# Exit status for a missing package, which analyze turns into that sentence.
MISSING_PACKAGE <- 3

check_packages <- function() {
  missing <- names(DEBIAN)[!vapply(names(DEBIAN), requireNamespace, logical(1), quietly = TRUE)]
  if (length(missing)) {
    message("mixed_models.R: R lacks the package(s) ", paste(missing, collapse = ", "),
            "; install them with: apt-get install ", paste(DEBIAN[missing], collapse = " "))
    quit(status = MISSING_PACKAGE)
  }
}

# A CSV of the export as text columns (an id "NA" stays "NA"): NULL when the file is not there,
# a sentence (a character string) when it cannot be read or lacks a column the models need.
read_export <- function(dir, name, required = character(0)) {
  path <- file.path(dir, name)
  if (!file.exists(path)) return(NULL)
  d <- tryCatch(read.csv(path, colClasses = "character", na.strings = character(0), check.names = FALSE,
                         encoding = "UTF-8", strip.white = FALSE),
                error = function(e) sprintf("%s cannot be read as CSV (%s): no models of its rows.", name,
                                            conditionMessage(e)))
  if (is.character(d)) return(d)
  if (!"condition" %in% names(d) && "mode" %in% names(d)) names(d)[names(d) == "mode"] <- "condition"
  missing <- setdiff(required, names(d))
  if (length(missing)) {
    return(sprintf("%s has no column %s: no models of its rows.", name, paste0("'", missing, "'", collapse = ", ")))
  }
  d
}

capitalise <- function(s) paste0(toupper(substr(s, 1, 1)), substring(s, 2))

is_true <- function(x) tolower(x) %in% c("true", "1")

# Rows of the scored phase, of the analysed participants, with a condition.
analysed_rows <- function(d) {
  if ("scored_phase" %in% names(d)) d <- d[is_true(d$scored_phase), , drop = FALSE]
  if (!is.null(SETTINGS$participants)) d <- d[d$participant %in% SETTINGS$participants, , drop = FALSE]
  d[d$condition != "", , drop = FALSE]
}

# Conditions in the report's order (others after them by name), the game's reference first.
condition_levels <- function(present, game) {
  order <- SETTINGS$condition_order
  lv <- c(order[order %in% present], sort(setdiff(present, order), method = "radix"))
  ref <- SETTINGS$reference[[game]]
  if (!is.null(ref) && ref %in% lv) lv <- c(ref, setdiff(lv, ref))
  lv
}

# The conditions conditions.csv lists for a game's analysed part (used_in "test", or every row
# of an export from before used_in).
listed_conditions <- function(conditions, game) {
  if (is.null(conditions) || !"game" %in% names(conditions)) return(character(0))
  rows <- conditions[conditions$game == game, , drop = FALSE]
  if ("used_in" %in% names(rows)) rows <- rows[rows$used_in == "test", , drop = FALSE]
  unique(rows$condition)
}

# One measure to model: its rows as participant, condition, y.
measure <- function(game, id, label, source, unit, engine, participant, condition, y, listed, extra = list()) {
  c(list(key = paste0(game, "/", id), game = game, measure = id, label = label, source = source, unit = unit,
         engine = engine, rows = data.frame(participant = participant, condition = condition, y = y,
                                            stringsAsFactors = FALSE), listed = listed), extra)
}

# Every game's hit per trial (shots.csv).
shot_measures <- function(dir, conditions, games) {
  shots <- read_export(dir, "shots.csv", c("participant", "game", "condition", "hit"))
  if (is.null(shots)) return(list(measures = list(), notes = "There is no shots.csv: no per-trial models."))
  if (is.character(shots)) return(list(measures = list(), notes = shots))
  shots <- analysed_rows(shots)
  if (nrow(shots) == 0) {
    return(list(measures = list(), notes = "shots.csv has no trial rows of the scored phase: no per-trial models."))
  }
  out <- lapply(unique(shots$game), function(game) {
    rows <- shots[shots$game == game, , drop = FALSE]
    words <- if (!is.null(games) && !is.character(games) && game %in% games$game) {
      games[games$game == game, ][1, ]
    } else list(hits_are = "hits", shots_are = "shots")
    measure(game, "hit", paste0(words$hits_are, " / ", words$shots_are, ", per trial"), "shots.csv", "trials",
            "binomial", rows$participant, rows$condition, as.integer(is_true(rows$hit)),
            listed_conditions(conditions, game))
  })
  list(measures = out, notes = character(0))
}

# The green hits of each scored match (matches.csv), for the game whose matches they are.
match_measures <- function(dir, conditions) {
  matches <- read_export(dir, "matches.csv", c("participant", "condition", "green_hits"))
  if (is.null(matches)) return(list(measures = list(), notes = character(0)))
  if (is.character(matches)) return(list(measures = list(), notes = matches))
  matches <- analysed_rows(matches)
  game <- if (is.null(SETTINGS$matches_game)) "matches" else SETTINGS$matches_game
  if (nrow(matches) == 0) return(list(measures = list(), notes = character(0)))
  list(measures = list(measure(game, "green_hits", "green hits per match", "matches.csv", "matches", "poisson",
                               matches$participant, matches$condition, as.numeric(matches$green_hits),
                               listed_conditions(conditions, game))),
       notes = character(0))
}

# Each Likert question's answers (answers.csv), per game and question.
likert_measures <- function(dir, conditions) {
  answers <- read_export(dir, "answers.csv", c("participant", "game", "condition", "kind", "question_index",
                                               "question_id", "prompt", "value"))
  if (is.null(answers)) return(list(measures = list(), notes = character(0)))
  if (is.character(answers)) return(list(measures = list(), notes = answers))
  notes <- character(0)
  likert <- answers[answers$kind == "likert", , drop = FALSE]
  mixed <- nrow(analysed_rows(likert)) - nrow(analysed_rows(likert[likert$condition != "", , drop = FALSE]))
  likert <- analysed_rows(likert)
  if (mixed > 0) {
    notes <- sprintf(paste("%d Likert answers of answers.csv are about blocks of interleaved conditions (an empty",
                           "condition): no condition to model them by, so they are left out."), mixed)
  }
  questions <- unique(likert[, c("game", "question_index", "question_id", "prompt")])
  out <- lapply(seq_len(nrow(questions)), function(q) {
    key <- questions[q, ]
    rows <- likert[likert$game == key$game & likert$question_index == key$question_index &
                   likert$question_id == key$question_id & likert$prompt == key$prompt, , drop = FALSE]
    id <- if (key$question_id != "") key$question_id else paste0("q", key$question_index)
    scale <- if (all(c("scale_min", "scale_max") %in% names(rows))) {
      c(as.numeric(rows$scale_min[1]), as.numeric(rows$scale_max[1]))
    } else NULL
    measure(key$game, paste0("likert:", id), key$prompt, "answers.csv", "answers", "clmm", rows$participant,
            rows$condition, suppressWarnings(as.numeric(rows$value)), listed_conditions(conditions, key$game),
            list(scale = scale, file_rows = as.integer(rownames(rows))))
  })
  list(measures = out, notes = notes)
}

measures_of <- function(dir) {
  conditions <- read_export(dir, "conditions.csv")
  if (is.character(conditions)) conditions <- NULL
  parts <- list(shot_measures(dir, conditions, read_export(dir, "games.csv")), match_measures(dir, conditions),
                likert_measures(dir, conditions))
  list(measures = do.call(c, lapply(parts, `[[`, "measures")), notes = unlist(lapply(parts, `[[`, "notes")))
}

# Sentences on what the data allow, and whether a model can be fitted at all.
check_measure <- function(m, rows) {
  notes <- character(0)
  stop_with <- function(...) list(fit = FALSE, notes = c(notes, sprintf(...)))
  absent <- setdiff(m$listed, rows$condition)
  if (length(absent)) {
    notes <- c(notes, sprintf("conditions.csv lists %s for the %s, but no participant has %s of %s: not a level of %s.",
                              paste(absent, collapse = ", "), m$game, m$unit, if (length(absent) > 1) "them" else "it",
                              "the model"))
  }
  if (!is.null(m$scale) && !anyNA(m$scale)) {
    out <- which(rows$y < m$scale[1] | rows$y > m$scale[2] | is.na(rows$y))
    if (length(out)) {
      return(stop_with("answers.csv, data row %d: the answer %s is outside the question's scale %g to %g, %s.",
                       m$file_rows[out[1]], rows$y[out[1]], m$scale[1], m$scale[2], "so this question is not modelled"))
    }
  }
  people <- unique(rows$participant)
  if (length(people) < 2) {
    return(stop_with("Only one participant (%s) has %s here: a mixed model needs several to estimate how %s.",
                     people[1], m$unit, "participants vary, so none is fitted"))
  }
  conds <- unique(rows$condition)
  if (length(conds) < 2) return(stop_with("Only one condition (%s): nothing to compare, so no model.", conds[1]))
  cells <- table(factor(rows$participant, levels = people), factor(rows$condition, levels = conds))
  lacking <- which(cells == 0, arr.ind = TRUE)
  if (nrow(lacking)) {
    says <- sprintf("%s lacks %s", rownames(cells)[lacking[, 1]], colnames(cells)[lacking[, 2]])
    notes <- c(notes, sprintf("Not every participant played every condition (%s); %s.", paste(says, collapse = "; "),
                              "the model uses each participant's other conditions"))
  }
  if (length(unique(rows$y)) == 1) {
    what <- if (m$engine == "binomial") (if (rows$y[1] == 1) "a hit" else "a miss") else paste("the answer", rows$y[1])
    return(stop_with("Every one of the %d %s is %s: there is no variation to model.", nrow(rows), m$unit, what))
  }
  flat <- flat_conditions(m, rows)
  if (length(flat)) {
    return(stop_with("%s: %s no finite estimate, so no model.", capitalise(paste(flat, collapse = "; ")),
                     if (m$engine == "poisson") "a log rate of 0 counts has" else "such log-odds have"))
  }
  if (m$engine == "binomial") notes <- c(notes, separation_sentence(rows, m$unit))
  list(fit = TRUE, notes = notes)
}

# Conditions whose every row has the same outcome, in words: a hit or miss everywhere (complete
# separation of that condition's log-odds), or no count at all.
flat_conditions <- function(m, rows) {
  flat <- character(0)
  for (c in unique(rows$condition)) {
    y <- rows$y[rows$condition == c]
    if (m$engine == "binomial" && length(unique(y)) == 1) {
      flat <- c(flat, sprintf("every one of the %d %s of %s is a %s", length(y), m$unit, c,
                              if (y[1] == 1) "hit" else "miss"))
    }
    if (m$engine == "poisson" && all(y == 0)) {
      flat <- c(flat, sprintf("every one of the %d %s of %s counts 0", length(y), m$unit, c))
    }
  }
  flat
}

# Quasi-separation: a participant with every trial of a condition a hit, or every one a miss.
separation_sentence <- function(rows, unit) {
  cells <- aggregate(y ~ participant + condition, data = rows, FUN = function(v) c(sum(v), length(v)))
  hits <- cells$y[, 1]
  n <- cells$y[, 2]
  edge <- which(hits == 0 | hits == n)
  if (length(edge) == 0) return(character(0))
  says <- sprintf("%s %s in %s (%d of %d)", cells$participant[edge], ifelse(hits[edge] == n[edge], "hit every one",
                                                                           "hit none"),
                  cells$condition[edge], hits[edge], n[edge])
  sprintf(paste("Separation: in %d participant-and-condition cell%s every one of the %s went the same way (%s).",
                "Their random effects keep the estimates finite, pulled towards the other participants; those",
                "participants' own odds there are not estimable."),
          length(edge), if (length(edge) > 1) "s" else "", unit, paste(says, collapse = "; "))
}

model_data <- function(m, rows) {
  levels <- condition_levels(unique(rows$condition), m$game)
  data <- data.frame(participant = factor(rows$participant, levels = unique(rows$participant)),
                     condition = factor(rows$condition, levels = levels))
  response <- c(binomial = "hit", poisson = "green_hits", clmm = "answer")[[m$engine]]
  data[[response]] <- if (m$engine == "clmm") factor(rows$y, levels = sort(unique(rows$y)), ordered = TRUE) else rows$y
  with_dummies <- add_dummies(data)
  list(data = with_dummies$data, dummies = with_dummies$columns, response = response)
}

# Per participant and condition: how many rows and their mean (a proportion of hits, a mean
# count or answer) -- the raw points the report's figure draws beside the model's means.
participant_points <- function(rows) {
  cells <- aggregate(y ~ participant + condition, data = rows, FUN = function(v) c(length(v), mean(v)))
  lapply(seq_len(nrow(cells)), function(i) list(participant = cells$participant[i], condition = cells$condition[i],
                                                n = cells$y[i, 1], mean = cells$y[i, 2]))
}

fit_measure <- function(m) {
  rows <- m$rows
  checked <- check_measure(m, rows)
  out <- list(key = m$key, game = m$game, measure = m$measure, label = m$label, source = m$source, unit = m$unit,
              n_participants = length(unique(rows$participant)), n_observations = nrow(rows),
              conditions = as.list(condition_levels(unique(rows$condition), m$game)),
              participant_points = participant_points(rows), fitted = FALSE, notes = as.list(checked$notes))
  if (!checked$fit) return(list(summary = out, saved = NULL))
  prepared <- model_data(m, rows)
  engine <- m$engine
  fitted <- fit_ladder(engine, prepared$response, prepared$data, prepared$dummies)
  if (engine == "poisson" && !is.null(fitted$fit)) {
    out$dispersion <- dispersion_of(fitted$fit)
    if (out$dispersion$overdispersed) {
      negbin <- fit_ladder("negbin", prepared$response, prepared$data, prepared$dummies, start = fitted$k)
      if (is.null(negbin$fit)) {
        why <- unlist(lapply(negbin$attempts, `[[`, "problems"))
        out$notes <- c(out$notes, sprintf("The negative binomial model could not be fitted (%s), so the Poisson %s",
                                          paste(why, collapse = "; "), "model is kept."))
      } else {
        out$poisson_attempts <- fitted$attempts
        engine <- "negbin"
        fitted <- negbin
      }
    }
  }
  if (is.null(fitted$fit)) {
    out$attempts <- fitted$attempts
    out$notes <- c(out$notes, "No model of the ladder could be fitted (the attempts say why).")
    return(list(summary = out, saved = NULL))
  }
  summary <- quietly(function() summarise_fit(fitted, engine, prepared$data, prepared$dummies,
                                              levels(prepared$data[[prepared$response]])))
  if (inherits(summary$value, "error")) {
    out$attempts <- fitted$attempts
    out$notes <- c(out$notes, paste("The model was fitted but emmeans could not summarise it:",
                                    conditionMessage(summary$value)))
    return(list(summary = out, saved = NULL))
  }
  out <- c(out, summary$value)
  out$fitted <- TRUE
  out$reference <- levels(prepared$data$condition)[1]
  out$n_participants <- nlevels(prepared$data$participant)
  # The formula as text, as the RDS's layout (this file's header) says: power.R and a reader's own
  # code read it with as.formula().
  saved <- list(model = fitted$fit, formula = paste(deparse(fitted$formula, width.cutoff = 500L), collapse = " "),
                engine = engine, step = fitted$step,
                reference = out$reference, data = prepared$data, dummies = prepared$dummies, game = m$game,
                measure = m$measure, label = m$label)
  list(summary = out, saved = saved)
}

# Printed numbers: 6 significant digits; the JSON keeps them all.
num <- function(x) ifelse(is.na(x), "NA", sprintf("%.6g", x))

print_model <- function(s) {
  cat(sprintf("\n== %s: %s (%s) ==\n", s$game, s$label, s$source))
  for (note in s$notes) cat("Note:", note, "\n")
  if (!isTRUE(s$fitted)) return(invisible())
  cat(sprintf("Fitted: %s; %d participants, %d %s\n", s$call_text, s$n_participants, s$n_observations, s$unit))
  if (!is.null(s$dispersion)) {
    d <- s$dispersion
    cat(sprintf("Poisson dispersion: Pearson chi2 = %s on %s df, ratio %s, p = %s -> %s\n", num(d$pearson_chisq),
                num(d$df), num(d$ratio), num(d$p), if (s$engine == "negbin") "negative binomial" else "Poisson kept"))
  }
  if (!is.null(s$theta)) cat(sprintf("Negative binomial theta = %s\n", num(s$theta)))
  for (a in c(s$poisson_attempts, s$attempts)) {
    verdict <- if (a$kept) paste(c("kept", a$problems), collapse = "; ") else
      paste("dropped:", paste(a$problems, collapse = "; "))
    cat(sprintf("  %s: %s -- %s\n", a$step, a$formula, verdict))
  }
  cat(sprintf("Reference level: %s\n", s$reference))
  cat(sprintf("Estimated %s per condition [95%% CI]:\n", s$means_scale))
  for (e in s$means) cat(sprintf("  %-24s %s [%s, %s]\n", e$condition, num(e$estimate), num(e$low), num(e$high)))
  cat(sprintf("%ss, a / b [95%% CI, unadjusted], p Holm-adjusted:\n", capitalise(s$ratio)))
  for (c in s$contrasts) {
    cat(sprintf("  %-40s %s [%s, %s]  p = %s\n", paste(c$a, "/", c$b), num(c$ratio), num(c$low), num(c$high),
                num(c$p_holm)))
  }
  cat("Random effects (SD, link scale):\n")
  for (r in s$random_effects$sds) cat(sprintf("  %s %s: %s\n", r$group, r$term, num(r$sd)))
  for (r in s$random_effects$correlations) cat(sprintf("  correlation %s, %s: %s\n", r$a, r$b, num(r$correlation)))
}

# JSON has no NaN or infinity: such numbers become null (NA).
finite <- function(x) {
  if (is.list(x)) return(lapply(x, finite))
  if (is.numeric(x)) x[!is.finite(x)] <- NA
  x
}

main <- function() {
  args <- commandArgs(trailingOnly = TRUE)
  export_dir <- if (length(args) >= 1) args[1] else SETTINGS$export_dir
  out_dir <- if (length(args) >= 2) args[2] else dirname(script_path())
  check_packages()
  if (!dir.exists(export_dir)) {
    message("mixed_models.R: ", export_dir, ": no such folder (expected the one `warplab export` wrote).")
    quit(status = 1)
  }
  found <- measures_of(export_dir)
  summaries <- list()
  models <- list()
  for (m in found$measures) {
    result <- tryCatch(fit_measure(m), error = function(e) {
      list(summary = list(key = m$key, game = m$game, measure = m$measure, label = m$label, source = m$source,
                          unit = m$unit, fitted = FALSE, conditions = list(), participant_points = list(),
                          n_participants = length(unique(m$rows$participant)), n_observations = nrow(m$rows),
                          notes = list(paste("R could not model these rows:", conditionMessage(e)))),
           saved = NULL)
    })
    summaries[[length(summaries) + 1]] <- result$summary
    if (!is.null(result$saved)) models[[m$key]] <- result$saved
  }
  cat(sprintf("Mixed models of %s (R %s; lme4 %s, emmeans %s, ordinal %s)\n", export_dir, getRversion(),
              packageVersion("lme4"), packageVersion("emmeans"), packageVersion("ordinal")))
  for (note in found$notes) cat("Note:", note, "\n")
  for (s in summaries) print_model(s)
  dir.create(out_dir, showWarnings = FALSE, recursive = TRUE)
  result <- list(export_dir = export_dir, r_version = as.character(getRversion()),
                 packages = lapply(setNames(names(DEBIAN), names(DEBIAN)), function(p) as.character(packageVersion(p))),
                 notes = as.list(found$notes), models = summaries)
  jsonlite::write_json(finite(result), file.path(out_dir, "mixed_models.json"), auto_unbox = TRUE, digits = NA,
                       null = "null", na = "null", pretty = TRUE)
  saveRDS(models, file.path(out_dir, "mixed_models.rds"))
}

# Any error left is R's, said in one line that analyze can quote.
tryCatch(main(), error = function(e) {
  message("mixed_models.R: ", conditionMessage(e))
  quit(status = 1)
})
