# Power of the report's trial-level mixed models by simulation: how many participants a study
# needs for a condition contrast to be found with 80 % power. What R's simr does (Green & MacLeod
# 2016), which Debian does not package, written here with lme4: studies drawn as its simulate()
# draws them, each refitted by glmer.
#
# Usage:
#   Rscript power.R RDS --out JSON [--model NAME]... [--effect A:B=RATIO]... [--contrast A:B]...
#     [--pairs reference|all] [--n N,N,... | --n-min N --n-max N] [--trials K] [--replicates R]
#     [--alpha A] [--target P] [--seed S] [--cores K] [--optimizer NAME] [--nagq 0|1]
#
# RDS is mixed_models.rds, as the report's mixed-model script saves it: a named list, one entry
# per game and measure ("shooter/hit"), each a list with `model` (the fitted glmerMod), `formula`
# (the kept formula, text), `reference` (the reference condition) and `data` (the frame it was
# fitted to: participant, condition, the response, and any numeric dummy columns the formula uses).
#
# For each model: take the pilot's fitted fixed effects (a stated --effect replaces its contrast)
# and random-effect covariances as the truth; simulate a study of n new participants, each with
# the pilot's trials per condition, drawing their random effects afresh; refit the kept formula;
# test each contrast by its Wald z; the power at n is the share of studies that reject. n is
# searched for the smallest with power >= target (doubling, then bisection), and for where the
# Clopper-Pearson interval of that share reaches the target. docs/export.md, "Sample size by
# simulation", says what is assumed and why.
#
# Exit status: 0, the JSON is written (a model that cannot be simulated is in it with the reason);
# 1, bad input: one sentence on stderr; 2, a bad command line; 3, R lacks a package it needs.

DEFAULTS <- list(replicates = 100L, alpha = 0.05, target = 0.8, seed = 1L, n_min = 4L, n_max = 64L,
                 optimizer = "nloptwrap", nagq = 0L, pairs = "reference")
# --pairs: which contrasts a model reports when neither --contrast nor --effect names them.
PAIRS <- c("reference", "all")
# Fewer pilot participants than this give the spread of participants' random effects from one or
# two values: a guess, not an estimate, and the simulation takes it as the truth.
FEWEST_PILOT_PARTICIPANTS <- 3L

say <- function(sentence, status) {
  cat("power.R: ", sentence, "\n", sep = "", file = stderr())
  quit(save = "no", status = status)
}
bad_input <- function(...) say(paste0(...), 1L)
# A model this script cannot simulate, for a reason in the model rather than in what was asked:
# plan_model's caller records it as skipped and goes on with the others.
cannot_simulate <- function(...) stop(structure(class = c("cannot_simulate", "error", "condition"),
                                                list(message = paste0(...), call = NULL)))
bad_usage <- function(...) say(paste0(..., " (usage: Rscript power.R RDS --out JSON [options];",
                                      " see the comment at its top)"), 2L)

whole <- function(text, flag, lowest) {
  value <- suppressWarnings(as.numeric(text))
  if (is.na(value) || value != round(value) || value < lowest)
    bad_usage(flag, " wants a whole number of at least ", lowest, ", not '", text, "'")
  as.integer(value)
}

fraction <- function(text, flag) {
  value <- suppressWarnings(as.numeric(text))
  if (is.na(value) || value <= 0 || value >= 1) bad_usage(flag, " wants a number between 0 and 1, not '", text, "'")
  value
}

parse_args <- function(args) {
  opts <- c(DEFAULTS, list(rds = NULL, out = NULL, models = character(), effects = character(),
                           contrasts = character(), n = NULL, trials = NULL, cores = NULL))
  repeated <- c("--model" = "models", "--effect" = "effects", "--contrast" = "contrasts")
  i <- 1L
  while (i <= length(args)) {
    flag <- args[[i]]
    if (!startsWith(flag, "--")) {
      if (!is.null(opts$rds)) bad_usage("one RDS file only, but '", flag, "' is a second")
      opts$rds <- flag
      i <- i + 1L
      next
    }
    if (i == length(args)) bad_usage(flag, " needs a value")
    value <- args[[i + 1L]]
    i <- i + 2L
    if (flag %in% names(repeated)) {
      opts[[repeated[[flag]]]] <- c(opts[[repeated[[flag]]]], value)
      next
    }
    switch(flag,
           "--out" = opts$out <- value,
           "--n" = opts$n <- sort(unique(vapply(strsplit(value, ",", fixed = TRUE)[[1]], whole, 1L, "--n", 2L))),
           "--n-min" = opts$n_min <- whole(value, flag, 2L),
           "--n-max" = opts$n_max <- whole(value, flag, 2L),
           "--trials" = opts$trials <- whole(value, flag, 1L),
           "--replicates" = opts$replicates <- whole(value, flag, 1L),
           "--alpha" = opts$alpha <- fraction(value, flag),
           "--target" = opts$target <- fraction(value, flag),
           "--seed" = opts$seed <- whole(value, flag, 0L),
           "--cores" = opts$cores <- whole(value, flag, 1L),
           "--optimizer" = opts$optimizer <- value,
           "--nagq" = opts$nagq <- if (value %in% c("0", "1")) as.integer(value) else
             bad_usage("--nagq wants 0 or 1, not '", value, "'"),
           "--pairs" = opts$pairs <- if (value %in% PAIRS) value else
             bad_usage("--pairs wants ", paste(PAIRS, collapse = " or "), ", not '", value, "'"),
           bad_usage("unknown option ", flag))
  }
  for (text in opts$effects) split_effect(text)  # its form now; its conditions per model
  if (is.null(opts$rds)) bad_usage("no RDS file given")
  if (is.null(opts$out)) bad_usage("no --out JSON given")
  if (opts$n_max < opts$n_min) bad_usage("--n-max ", opts$n_max, " is below --n-min ", opts$n_min)
  if (is.null(opts$cores)) opts$cores <- max(1L, parallel::detectCores(), na.rm = TRUE)
  opts
}

# "A:B=RATIO" against the model's conditions: condition names may hold ":" themselves, so every
# split at a ":" is tried and the one naming two conditions kept. NULL when this model lacks them.
parse_pair <- function(text, conditions) {
  colons <- gregexpr(":", text, fixed = TRUE)[[1]]
  for (at in colons[colons > 0]) {
    a <- substr(text, 1L, at - 1L)
    b <- substr(text, at + 1L, nchar(text))
    if (a %in% conditions && b %in% conditions && a != b) return(c(a, b))
  }
  NULL
}

split_effect <- function(text) {
  at <- regexpr("=[^=]*$", text)
  ratio <- if (at > 0) suppressWarnings(as.numeric(substring(text, at + 1L))) else NA
  if (at <= 1 || is.na(ratio) || !is.finite(ratio) || ratio <= 0)
    bad_usage("--effect wants A:B=RATIO with a ratio above 0, not '", text, "'")
  list(pair = substr(text, 1L, at - 1L), ratio = ratio)
}

# Why this entry cannot be simulated, or NULL when it can.
unusable <- function(entry) {
  if (!is.list(entry) || !all(c("model", "formula", "reference", "data") %in% names(entry)))
    return("the entry lacks one of model, formula, reference and data")
  model <- entry$model
  if (!inherits(model, "glmerMod")) return("it is not a glmer fit (only binomial and Poisson GLMMs are simulated)")
  fam <- family(model)
  if (!paste(fam$family, fam$link) %in% c("binomial logit", "poisson log"))
    return(paste0("its family is ", fam$family, " (", fam$link, "); only binomial (logit) and Poisson (log) ",
                  "are simulated"))
  groups <- names(getME(model, "flist"))
  if (!identical(groups, "participant"))
    return(paste0("its random effects are grouped by ", paste(groups, collapse = " and "),
                  "; new studies draw new participants only"))
  data <- entry$data
  if (!all(c("participant", "condition") %in% names(data))) return("its data lacks participant or condition")
  people <- length(unique(data$participant))
  if (people < FEWEST_PILOT_PARTICIPANTS)
    return(paste0("the pilot has too little data: ", people, " participant", if (people == 1) "" else "s",
                  ", where the spread of participants' random effects needs at least ", FEWEST_PILOT_PARTICIPANTS))
  NULL
}

# The model's conditions in its level order, the reference first (as glmer makes a factor of text).
conditions_of <- function(model) {
  conditions <- model@frame$condition
  if (is.factor(conditions)) levels(conditions) else sort(unique(as.character(conditions)))
}

# What each new participant plays: per condition, the pilot's median trials (or --trials), with
# the value every other column the formula uses has in that condition (the dummy columns of
# uncorrelated slopes): such a column must be constant within a condition.
design_of <- function(entry, trials) {
  model <- entry$model
  data <- as.data.frame(entry$data)
  conditions <- conditions_of(model)
  response <- all.vars(formula(model))[1]
  carried <- setdiff(all.vars(formula(model)), c(response, "participant", "condition"))
  rows <- lapply(conditions, function(cond) {
    here <- data[data$condition == cond, , drop = FALSE]
    if (nrow(here) == 0) cannot_simulate("the pilot has no trials in ", cond)
    k <- if (is.null(trials)) max(1L, as.integer(round(median(table(as.character(here$participant)))))) else trials
    for (column in carried) if (length(unique(here[[column]])) != 1)
      cannot_simulate("its column ", column, " varies within condition ", cond,
                ", so new participants' values of it cannot be known")
    row <- data.frame(condition = rep(cond, k), stringsAsFactors = FALSE)
    for (column in carried) row[[column]] <- rep(here[[column]][1], k)
    row
  })
  template <- do.call(rbind, rows)
  template$condition <- factor(template$condition, levels = conditions)
  template[[response]] <- 0  # simulate() evaluates the model frame, response included
  list(template = template, response = response, conditions = conditions,
       trials = setNames(as.list(vapply(rows, nrow, 1L)), conditions))
}

new_study <- function(design, n) {
  study <- design$template[rep(seq_len(nrow(design$template)), n), , drop = FALSE]
  # New ids, so no participant's pilot random effect carries over (re.form = NA draws them all).
  study$participant <- factor(rep(sprintf("new%04d", seq_len(n)), each = nrow(design$template)))
  rownames(study) <- NULL
  study
}

coefficient_of <- function(condition, reference) if (condition == reference) NA else paste0("condition", condition)

# A contrast's row of L, so that L %*% beta is log(ratio of a against b).
contrast_row <- function(a, b, reference, beta) {
  row <- setNames(numeric(length(beta)), names(beta))
  for (side in list(c(a, 1), c(b, -1))) {
    name <- coefficient_of(side[[1]], reference)
    if (!is.na(name)) {
      if (!name %in% names(beta)) cannot_simulate("its fixed effects have no ", name, " (treatment coding against ",
                                           reference, " expected)")
      row[[name]] <- as.numeric(side[[2]])
    }
  }
  row
}

# The pilot's fixed effects with each stated contrast put in: A:B=RATIO sets log(ratio) as A's
# contrast with B by moving A's coefficient (B's when A is the reference), so every other contrast
# with B keeps the pilot's value. Stated contrasts that contradict each other are refused.
apply_effects <- function(beta, effects, reference, name) {
  for (e in effects) {
    row <- contrast_row(e$a, e$b, reference, beta)
    gap <- log(e$ratio) - sum(row * beta)
    moved <- if (e$a != reference) coefficient_of(e$a, reference) else coefficient_of(e$b, reference)
    beta[[moved]] <- beta[[moved]] + gap * row[[moved]]
  }
  for (e in effects)
    if (abs(sum(contrast_row(e$a, e$b, reference, beta) * beta) - log(e$ratio)) > 1e-9)
      bad_input("the stated effects contradict each other in ", name, ": ", e$text, " no longer holds once ",
                "the others are put in")
  beta
}

# Clopper-Pearson interval of a share (binom.test's), and the power's summary at one n.
share <- function(rejections, replicates) {
  ci <- binom.test(rejections, replicates)$conf.int
  list(power = rejections / replicates, low = ci[[1]], high = ci[[2]])
}

# lme4's own model structure for a study of n new participants (glFormula: X, Zt, and Lambdat
# filled from theta through Lind), built once per n, so that each replicate draws its response
# as simulate(model, newdata = study, newparams = ..., re.form = NA, allow.new.levels = TRUE)
# would -- the same normal draws for u, then the same rbinom or rpois calls, hence the same
# response for the same stream (analysis/tests/test_power.py checks it) -- without redoing that
# structure for every replicate (a third of each replicate's time with a random intercept).
study_structure <- function(ctx, n) {
  study <- new_study(ctx$design, n)
  parts <- glFormula(ctx$formula, data = study, family = ctx$family)
  lambdat <- parts$reTrms$Lambdat
  lambdat@x <- ctx$params$theta[parts$reTrms$Lind]
  list(study = study, X = parts$X, Zt = parts$reTrms$Zt, Lambdat = lambdat)
}

# The fit each replicate at n refits with its own response (lme4's refit, as bootMer does): half
# the time of a fresh glmer, which rebuilds the model frame and structure every time, for fixed
# effects and standard errors within 1e-4 of it (the refit starts from this fit's estimates). Fitted
# here, before any work is shared out, to replicate 1's response, so every worker refits the same
# fit; NULL when that fit fails, and each replicate is then fitted afresh.
with_template <- function(structure, ctx) {
  assign(".Random.seed", ctx$streams[[1]], envir = globalenv())
  structure$study[[ctx$design$response]] <- simulate_response(structure, ctx$params$beta, ctx$family)
  structure$template <- tryCatch(suppressWarnings(suppressMessages(fit_study(structure$study, ctx))),
                                 error = function(e) NULL)
  structure
}

fit_study <- function(study, ctx)
  glmer(ctx$formula, data = study, family = ctx$family, control = ctx$control, nAGQ = ctx$nagq)

simulate_response <- function(structure, beta, family) {
  u <- rnorm(nrow(structure$Zt))
  eta <- as.vector(structure$X %*% beta[colnames(structure$X)] +
                     Matrix::crossprod(structure$Zt, Matrix::crossprod(structure$Lambdat, u)))
  mu <- family$linkinv(eta)
  if (family$family == "binomial") rbinom(length(mu), 1, mu) / 1 else rpois(length(mu), mu)
}

# One simulated study under replicate r's random stream: every contrast's rejection (NA for all
# when the refit failed) and whether the refit was singular or warned.
one_study <- function(r, structure, ctx) {
  assign(".Random.seed", ctx$streams[[r]], envir = globalenv())
  response <- simulate_response(structure, ctx$params$beta, ctx$family)
  warned <- FALSE
  fit <- tryCatch(withCallingHandlers(
    if (!is.null(structure$template)) refit(structure$template, newresp = response)
    else fit_study(replace(structure$study, ctx$design$response, list(response)), ctx),
    warning = function(w) { warned <<- TRUE; invokeRestart("muffleWarning") },
    message = function(m) invokeRestart("muffleMessage")), error = function(e) NULL)
  none <- rep(NA, nrow(ctx$L))
  if (is.null(fit)) return(list(reject = none, failed = TRUE, singular = NA, warned = warned))
  names <- colnames(ctx$L)
  se <- sqrt(diag(ctx$L %*% as.matrix(vcov(fit))[names, names] %*% t(ctx$L)))
  reject <- 2 * pnorm(-abs(as.vector(ctx$L %*% fixef(fit)[names]) / se)) < ctx$alpha
  if (anyNA(reject)) return(list(reject = none, failed = TRUE, singular = NA, warned = warned))
  list(reject = reject, failed = FALSE, singular = isSingular(fit), warned = warned)
}

# Workers forked once per model, after a fit in this process has loaded what glmer needs: a child
# forked before that pays lme4's lazy loading itself, about as long as several fits, and forking
# for every batch (mclapply) cost as much again. With one core the replicates run here.
start_workers <- function(ctx, cores) {
  if (cores < 2L) return(NULL)
  workers <- tryCatch(parallel::makeForkCluster(cores), error = function(e) {
    cat("power.R: no workers (", conditionMessage(e), "), so one core\n", sep = "", file = stderr())
    NULL
  })
  if (is.null(workers)) return(NULL)
  parallel::clusterExport(workers, "ctx", envir = environment())
  workers
}
in_worker <- function(r) one_study(r, get("structure", envir = globalenv()), get("ctx", envir = globalenv()))

# Each n's structure (its template fit included) goes to the workers once, not with every batch.
share_structure <- function(workers, structure) {
  if (!is.null(workers))
    parallel::clusterCall(workers, function(s) assign("structure", s, envir = globalenv()), structure)
  invisible(NULL)
}

run_batch <- function(batch, structure, ctx, workers) {
  tryCatch(if (is.null(workers)) lapply(batch, one_study, structure = structure, ctx = ctx)
           else parallel::parLapply(workers, batch, in_worker),
           error = function(e) bad_input("a simulated study of ", ctx$name, " failed in R: ", conditionMessage(e)))
}

# Runs the replicates at n (cached: the searches ask for the same n again), in batches of BATCH,
# stopping once every contrast's interval lies wholly on one side of the target: such an n answers
# every question the searches ask (power, and either limit, against the target) with fewer fits;
# the n near the answer get every replicate. Each replicate takes its own stream, fixed before any
# work is shared out, so the answer does not depend on the cores; replicate r uses the same stream
# at every n (common random numbers), which smooths the curve.
BATCH <- 25L
evaluator <- function(ctx, workers, target) {
  cache <- list()
  function(n) {
    key <- as.character(n)
    if (is.null(cache[[key]])) {
      started <- proc.time()[["elapsed"]]
      structure <- with_template(study_structure(ctx, n), ctx)
      share_structure(workers, structure)
      runs <- list()
      while (length(runs) < length(ctx$streams)) {
        batch <- seq(length(runs) + 1L, min(length(runs) + BATCH, length(ctx$streams)))
        runs <- c(runs, run_batch(batch, structure, ctx, workers))
        rejected <- rowSums(matrix(vapply(runs, function(x) x$reject %in% TRUE, logical(nrow(ctx$L))),
                                   nrow = nrow(ctx$L)))
        decided <- vapply(rejected, function(k) with(share(k, length(runs)), low > target || high < target), TRUE)
        if (all(decided)) break
      }
      cache[[key]] <<- list(n = n, rejections = rejected, replicates = length(runs),
                            failed = sum(vapply(runs, `[[`, TRUE, "failed")),
                            singular = sum(vapply(runs, function(x) x$singular %in% TRUE, TRUE)),
                            warned = sum(vapply(runs, `[[`, TRUE, "warned")),
                            seconds = round(proc.time()[["elapsed"]] - started, 3))
      cat(sprintf("power.R: %s, n = %d: %d studies, %.0f s\n", ctx$name, n, length(runs), cache[[key]]$seconds),
          file = stderr())
    }
    cache[[key]]
  }
}

# How finely the search pins n down: to the participant up to 10, then to within a fifth. The
# Monte-Carlo interval of the power at the default replicates spans more than that (at the demo's
# effects, its N range spans a third to a half of N), and each larger n costs more.
RESOLUTION <- 0.2
tolerance <- function(n) max(1L, as.integer(floor(RESOLUTION * n)))

# The smallest n among `candidates` (ascending) where ok(n), bisecting the gap below it (when
# `bisect`) down to the tolerance; NA when none. Assumes ok is monotone in n, as power is, up to
# Monte-Carlo noise.
first_n <- function(ok, candidates, bisect) {
  below <- NA
  for (n in candidates) {
    if (ok(n)) {
      while (bisect && !is.na(below) && n - below > tolerance(n)) {
        mid <- (below + n) %/% 2L
        if (ok(mid)) n <- mid else below <- mid
      }
      return(n)
    }
    below <- n
  }
  NA
}

upto <- function(candidates, most) unique(as.integer(pmin(candidates, most)))

# For contrast k: the smallest n with the target power. A search doubles n from --n-min up to
# --n-max, then bisects; with --n, the given n only.
needed_n <- function(k, evaluate, opts) {
  reaches <- function(n) with(evaluate(n), rejections[[k]] / replicates) >= opts$target
  given <- !is.null(opts$n)
  first_n(reaches, if (given) opts$n else upto(opts$n_min * 2^(0:30), opts$n_max), !given)
}

# Where N could be, given the simulation's own noise, among the n simulated for any contrast: from
# the first n whose Monte-Carlo interval reaches the target to the first whose interval lies
# wholly above it; NA for an end no n simulated shows. Searching each end further would cost
# studies at more n, for a precision the interval itself does not have.
n_range <- function(curve, target) {
  first <- function(limit) {
    n <- vapply(Filter(function(p) p[[limit]] >= target, curve), `[[`, 1, "n")
    if (length(n)) as.integer(min(n)) else NA
  }
  c(first("high"), first("low"))
}

# The contrasts to report for one model: those --contrast names, else those --effect states,
# else (--pairs reference, the default) each condition against the reference, or (--pairs all)
# every pair, each later condition (in the model's level order, reference first) against each
# earlier one. Either way a contrast with the reference reads as its coefficient. Every pair of
# seven conditions is 21 contrasts, whose searches visit more n, each costing a full set of
# studies; against the reference they are 6, the questions a study is usually planned for.
contrasts_of <- function(opts, effects, conditions) {
  if (length(opts$contrasts)) {
    pairs <- lapply(opts$contrasts, parse_pair, conditions)
    return(pairs[!vapply(pairs, is.null, TRUE)])
  }
  if (length(effects)) return(lapply(effects, function(e) c(e$a, e$b)))
  earlier <- function(j) if (opts$pairs == "all") seq_len(j - 1L) else 1L
  pairs <- list()
  for (j in seq_along(conditions)[-1]) for (i in earlier(j)) pairs[[length(pairs) + 1L]] <- conditions[c(j, i)]
  pairs
}

plan_model <- function(name, entry, opts, streams) {
  entry$name <- name
  why <- unusable(entry)
  if (!is.null(why)) return(list(model = name, skipped = why))
  model <- entry$model
  design <- design_of(entry, opts$trials)
  reference <- design$conditions[[1]]
  if (!is.null(entry$reference) && !identical(as.character(entry$reference), reference))
    cannot_simulate("its reference is ", entry$reference, " but its model's first condition level is ", reference)
  effects <- Filter(Negate(is.null), lapply(opts$effects, function(text) {
    e <- split_effect(text)
    pair <- parse_pair(e$pair, design$conditions)
    if (is.null(pair)) NULL else list(a = pair[[1]], b = pair[[2]], ratio = e$ratio, text = text)
  }))
  pilot <- fixef(model)
  beta <- apply_effects(pilot, effects, reference, name)
  pairs <- contrasts_of(opts, effects, design$conditions)
  if (!length(pairs))
    return(list(model = name, skipped = "none of the contrasts asked for is between two of its conditions"))
  L <- do.call(rbind, lapply(pairs, function(p) contrast_row(p[[1]], p[[2]], reference, beta)))
  fam <- family(model)
  ctx <- list(name = name, design = design, params = list(beta = beta, theta = getME(model, "theta")),
              formula = as.formula(entry$formula, env = globalenv()), family = fam, alpha = opts$alpha, L = L,
              streams = streams, control = glmerControl(optimizer = opts$optimizer, calc.derivs = FALSE),
              nagq = opts$nagq)
  # The pilot refitted here first: it loads glmer's code before the workers fork (start_workers).
  tryCatch(suppressWarnings(suppressMessages(fit_study(entry$data, ctx))),
           error = function(e) cannot_simulate("its kept formula does not refit to its own data: ",
                                         conditionMessage(e)))
  workers <- start_workers(ctx, opts$cores)
  on.exit(if (!is.null(workers)) parallel::stopCluster(workers))
  evaluate <- evaluator(ctx, workers, opts$target)
  stated <- vapply(pairs, function(p) any(vapply(effects, function(e) e$a == p[[1]] && e$b == p[[2]], TRUE)), TRUE)
  contrasts <- lapply(seq_along(pairs), function(k) {
    list(a = pairs[[k]][[1]], b = pairs[[k]][[2]], log_ratio = sum(L[k, ] * beta), ratio = exp(sum(L[k, ] * beta)),
         pilot_ratio = exp(sum(L[k, ] * pilot)), source = if (stated[[k]]) "stated" else "pilot",
         needed = needed_n(k, evaluate, opts))
  })
  evaluated <- evaluate_all(evaluate, environment(evaluate)$cache)
  for (k in seq_along(contrasts)) {
    contrasts[[k]]$curve <- lapply(evaluated, function(e) c(list(n = e$n), share(e$rejections[[k]], e$replicates),
                                                            list(rejections = e$rejections[[k]])))
    contrasts[[k]]$range <- n_range(contrasts[[k]]$curve, opts$target)
    if (!is.na(contrasts[[k]]$needed))
      contrasts[[k]]$at_needed <- with(evaluate(contrasts[[k]]$needed), share(rejections[[k]], replicates))
  }
  sds <- as.data.frame(VarCorr(model))
  list(model = name, formula = entry$formula, family = fam$family, link = fam$link,
       ratio_name = if (fam$link == "logit") "odds ratio" else "rate ratio", reference = reference,
       conditions = design$conditions, pilot = list(participants = length(unique(entry$data$participant)),
                                                    singular = isSingular(model)),
       trials_per_condition = design$trials, fixed_effects = as.list(beta), pilot_fixed_effects = as.list(pilot),
       random_effects = lapply(seq_len(nrow(sds)), function(i) as.list(sds[i, ])),
       studies = lapply(evaluated, function(e) e[c("n", "replicates", "failed", "singular", "warned", "seconds")]),
       contrasts = contrasts)
}

# Every n evaluated, ascending.
evaluate_all <- function(evaluate, cache) {
  ns <- sort(as.integer(names(cache)))
  lapply(ns, evaluate)
}

main <- function(args) {
  opts <- parse_args(args)
  for (package in c("lme4", "jsonlite"))
    if (!requireNamespace(package, quietly = TRUE))
      say(paste0("R lacks the package ", package, " (Debian: apt-get install r-cran-", tolower(package), ")"), 3L)
  suppressPackageStartupMessages(library(lme4))
  if (!file.exists(opts$rds)) bad_input(opts$rds, ": no such file")
  models <- tryCatch(readRDS(opts$rds), error = function(e) bad_input(opts$rds, ": not an RDS file R can read"))
  # An empty list is what the mixed-model script saves when it fitted nothing: nothing to plan.
  if (!is.list(models) || (length(models) && is.null(names(models))))
    bad_input(opts$rds, ": not a named list of fitted models")
  chosen <- if (length(opts$models)) opts$models else names(models)
  unknown <- setdiff(chosen, names(models))
  if (length(unknown)) bad_input(opts$rds, " has no model ", unknown[[1]], " (it has ",
                                 paste(names(models), collapse = ", "), ")")
  known <- lapply(models[chosen], function(e) if (is.list(e) && inherits(e$model, "merMod")) conditions_of(e$model))
  for (text in opts$effects)  # a misspelt condition is caught before any study is simulated
    if (!any(vapply(known, function(k) !is.null(parse_pair(split_effect(text)$pair, k)), TRUE)))
      bad_input("no model has both conditions of ", text)
  RNGkind("L'Ecuyer-CMRG")
  set.seed(opts$seed)
  streams <- vector("list", opts$replicates)
  stream <- .Random.seed
  for (r in seq_len(opts$replicates)) streams[[r]] <- stream <- parallel::nextRNGStream(stream)
  started <- proc.time()[["elapsed"]]
  planned <- lapply(chosen, function(name) tryCatch(plan_model(name, models[[name]], opts, streams),
                                                    cannot_simulate = function(e) list(model = name,
                                                                                       skipped = conditionMessage(e))))
  result <- list(test = "Wald z", alpha = opts$alpha, target = opts$target, replicates = opts$replicates,
                 pairs = opts$pairs, seed = opts$seed, cores = opts$cores, optimizer = opts$optimizer,
                 nagq = opts$nagq,
                 search = if (is.null(opts$n)) list(n_min = opts$n_min, n_max = opts$n_max, n = NULL)
                          else list(n_min = NULL, n_max = NULL, n = opts$n),
                 trials = opts$trials, effects = opts$effects, contrasts = opts$contrasts, models = planned,
                 seconds = round(proc.time()[["elapsed"]] - started, 3),
                 versions = list(R = paste(R.version$major, R.version$minor, sep = "."),
                                 lme4 = as.character(packageVersion("lme4"))))
  text <- jsonlite::toJSON(result, auto_unbox = TRUE, null = "null", na = "null", digits = NA, pretty = TRUE)
  writeLines(text, opts$out)
}

# Not when source()d, as the tests do. An error nothing above foresaw still ends in one sentence.
if (sys.nframe() == 0L)
  tryCatch(main(commandArgs(trailingOnly = TRUE)),
           error = function(e) say(paste0("R stopped: ", sub("\\.?\\s*$", "", conditionMessage(e))), 1L))
