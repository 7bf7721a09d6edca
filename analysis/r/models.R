# models.R -- fitting one trial-level mixed model and summarising it: the helpers of
# mixed_models.R, which reads the export and calls them once per game and measure. analyze
# copies this file into the mixed_models.R it writes beside a report, so that script stands alone.
#
# The random-effects structure starts maximal for the design (Barr et al. 2013: a random slope
# for every within-participant factor, here condition) and steps down only when the data cannot
# support it -- a singular fit (lme4::isSingular: a variance estimated at 0 or a correlation at
# +-1) or no convergence -- first to uncorrelated random effects, then to a random intercept
# (Matuschek et al. 2017 argue for that parsimony). Uncorrelated random slopes of a factor need
# numeric dummy columns: lme4 expands `(1 + condition || participant)` into
# `(1 | participant) + (0 + condition | participant)`, which keeps the correlations between the
# condition levels; afex does the same with its expand_re.

# The steps of the ladder, richest first.
MAXIMAL <- "maximal"
ZERO_CORRELATION <- "uncorrelated"
INTERCEPT <- "random intercept"

# Below this a clmm's participant SD (latent logit scale) counts as 0: isSingular does not know
# clmm, and ordinal optimises the log of the SD, which stops short of 0 where the estimate is 0.
SINGULAR_SD <- 0.01
# Overdispersion: a Poisson model's Pearson chi-square against its residual df at this level
# (Bolker et al. 2009) sends the counts to a negative binomial.
OVERDISPERSION_ALPHA <- 0.05

# What a model is, by engine: the R call's name, the family in words, what its EMMs are on the
# response scale and what a ratio of two conditions is.
ENGINES <- list(
  binomial = list(call = "lme4::glmer", family = "binomial(link = \"logit\")", scale = "probability",
                  ratio = "odds ratio"),
  poisson = list(call = "lme4::glmer", family = "poisson(link = \"log\")", scale = "count",
                 ratio = "rate ratio"),
  negbin = list(call = "lme4::glmer.nb", family = "negative binomial (log link)", scale = "count",
                ratio = "rate ratio"),
  clmm = list(call = "ordinal::clmm", family = "cumulative logit", scale = "mean answer",
              ratio = "cumulative odds ratio"))

# Runs f(), keeping its warnings and messages instead of printing them; an error is returned.
quietly <- function(f) {
  warnings <- character(0)
  messages <- character(0)
  value <- withCallingHandlers(
    tryCatch(f(), error = function(e) e),
    warning = function(w) {
      warnings <<- c(warnings, conditionMessage(w))
      invokeRestart("muffleWarning")
    },
    message = function(m) {
      messages <<- c(messages, trimws(conditionMessage(m)))
      invokeRestart("muffleMessage")
    })
  list(value = value, warnings = unique(warnings), messages = unique(messages))
}

# Numeric dummy columns, one per condition level after the reference, for uncorrelated random
# slopes: d_2 is 1 in the second level, and so on. Returns the data and {column: level}.
add_dummies <- function(data) {
  lv <- levels(data$condition)
  columns <- character(0)
  for (k in seq_along(lv)[-1]) {
    name <- paste0("d_", k)
    data[[name]] <- as.numeric(data$condition == lv[k])
    columns[name] <- lv[k]
  }
  list(data = data, columns = columns)
}

# The formulas to try, richest first: {step name: formula text}.
ladder <- function(response, dummies, engine) {
  fixed <- paste(response, "~ condition")
  intercept <- paste(fixed, "+ (1 | participant)")
  if (engine == "clmm" || length(dummies) == 0) {
    return(setNames(list(intercept), INTERCEPT))
  }
  steps <- list(paste(fixed, "+ (1 + condition | participant)"),
                paste0(fixed, " + (1 + ", paste(names(dummies), collapse = " + "), " || participant)"),
                intercept)
  setNames(steps, c(MAXIMAL, ZERO_CORRELATION, INTERCEPT))
}

# nloptwrap (nlopt's BOBYQA) rather than glmer's default minqa bobyqa: the same optimum, found in
# seconds rather than tens of them for a maximal model of seven conditions (28 covariance terms).
OPTIMIZER <- "nloptwrap"

fit_once <- function(engine, formula, data, derivs = TRUE, start = NULL) {
  control <- lme4::glmerControl(optimizer = OPTIMIZER, calc.derivs = derivs)
  switch(engine,
         binomial = lme4::glmer(formula, data = data, family = binomial(link = "logit"), control = control,
                                start = start),
         poisson = lme4::glmer(formula, data = data, family = poisson(link = "log"), control = control, start = start),
         negbin = lme4::glmer.nb(formula, data = data, control = control),
         clmm = ordinal::clmm(formula, data = data))
}

# One step's fit, quietly. A glmer fit is first made without the derivatives lme4's convergence
# check needs (finite differences over every parameter: most of the time a maximal model takes):
# a singular fit is dropped whatever they would say; any other is fitted again from where the
# first stopped, with them.
fit_step <- function(engine, formula, data) {
  if (!engine %in% c("binomial", "poisson")) return(quietly(function() fit_once(engine, formula, data)))
  quick <- quietly(function() fit_once(engine, formula, data, derivs = FALSE))
  if (inherits(quick$value, "error") || lme4::isSingular(quick$value)) return(quick)
  start <- list(theta = lme4::getME(quick$value, "theta"), fixef = lme4::fixef(quick$value))
  quietly(function() fit_once(engine, formula, data, start = start))
}

# Why a fit cannot be kept: "singular" and/or what stopped it converging; character(0) when it can.
problems_of <- function(engine, fit, warnings) {
  if (engine == "clmm") {
    sds <- participant_sds(fit)
    out <- if (any(sds < SINGULAR_SD)) "singular (the participants' SD is estimated at 0)" else character(0)
    if (!is.null(fit$optRes$convergence) && fit$optRes$convergence != 0) {
      out <- c(out, paste("did not converge:", fit$optRes$message))
    }
    return(c(out, if (length(warnings)) paste("did not converge:", warnings[1])))
  }
  out <- character(0)
  if (lme4::isSingular(fit)) {
    out <- "singular (lme4::isSingular: a random-effect variance at 0 or a correlation at +-1)"
  }
  messages <- unique(c(unlist(fit@optinfo$conv$lme4$messages), unlist(fit@optinfo$warnings), warnings))
  messages <- messages[!grepl("singular", messages)]
  # minqa's advice on its evaluation budget, not a failure to converge.
  messages <- messages[!grepl("maxfun < 10 \\* length\\(par\\)\\^2", messages)]
  if (!is.null(fit@optinfo$conv$opt) && fit@optinfo$conv$opt != 0) {
    messages <- c(sprintf("the optimizer stopped with code %s", fit@optinfo$conv$opt), messages)
  }
  if (length(messages)) out <- c(out, paste("did not converge:", messages[1]))
  out
}

# Fits the ladder from `start` down; keeps the first fit without problems, else the last that
# fitted at all. Returns list(fit, step, formula, attempts), fit NULL when nothing fitted.
fit_ladder <- function(engine, response, data, dummies, start = 1) {
  steps <- ladder(response, dummies, engine)
  attempts <- list()
  kept <- NULL
  for (k in seq_along(steps)[seq_along(steps) >= start]) {
    formula <- as.formula(steps[[k]], env = globalenv())
    run <- fit_step(engine, formula, data)
    fit <- run$value
    problems <- if (inherits(fit, "error")) paste("failed:", conditionMessage(fit)) else
      problems_of(engine, fit, run$warnings)
    attempts[[length(attempts) + 1]] <- list(step = names(steps)[k], formula = steps[[k]],
                                             problems = as.list(problems), kept = FALSE)
    if (!inherits(fit, "error")) {
      kept <- list(fit = fit, step = names(steps)[k], formula = formula, index = length(attempts), k = k)
      if (length(problems) == 0) break
    }
  }
  if (is.null(kept)) return(list(fit = NULL, attempts = attempts))
  attempts[[kept$index]]$kept <- TRUE
  list(fit = kept$fit, step = kept$step, formula = kept$formula, k = kept$k, attempts = attempts)
}

# A Poisson fit's Pearson chi-square over its residual degrees of freedom.
dispersion_of <- function(fit) {
  chisq <- sum(residuals(fit, type = "pearson")^2)
  df <- df.residual(fit)
  p <- pchisq(chisq, df = df, lower.tail = FALSE)
  list(pearson_chisq = chisq, df = df, ratio = chisq / df, p = p, overdispersed = p < OVERDISPERSION_ALPHA)
}

participant_sds <- function(fit) {
  if (inherits(fit, "clmm")) return(unname(attr(ordinal::VarCorr(fit)$participant, "stddev")))
  vc <- as.data.frame(lme4::VarCorr(fit))
  vc$sdcor[is.na(vc$var2)]
}

# A random-effect term in the report's words: the intercept, or the participant's deviation in
# the difference a condition (or its dummy column) makes against the reference.
term_label <- function(term, levels, dummies) {
  if (term == "(Intercept)") return("intercept")
  if (term %in% names(dummies)) return(paste(dummies[[term]], "-", levels[1]))
  if (startsWith(term, "condition") && substring(term, 10) %in% levels) {
    return(paste(substring(term, 10), "-", levels[1]))
  }
  term
}

random_effects <- function(fit, levels, dummies) {
  if (inherits(fit, "clmm")) {
    return(list(sds = list(list(group = "participant", term = "intercept", sd = participant_sds(fit)[1])),
                correlations = list()))
  }
  vc <- as.data.frame(lme4::VarCorr(fit))
  sds <- lapply(which(is.na(vc$var2)), function(i) {
    # lme4 names the uncorrelated terms' groups participant, participant.1, ...: one factor.
    list(group = sub("\\.[0-9]+$", "", vc$grp[i]), term = term_label(vc$var1[i], levels, dummies), sd = vc$sdcor[i])
  })
  correlations <- lapply(which(!is.na(vc$var2)), function(i) {
    list(group = sub("\\.[0-9]+$", "", vc$grp[i]), a = term_label(vc$var1[i], levels, dummies),
         b = term_label(vc$var2[i], levels, dummies), correlation = vc$sdcor[i])
  })
  list(sds = sds, correlations = correlations)
}

fixed_effects <- function(fit) {
  if (inherits(fit, "clmm")) {
    est <- fit$beta
    se <- sqrt(diag(vcov(fit)))[names(est)]
  } else {
    est <- lme4::fixef(fit)
    se <- sqrt(diag(as.matrix(vcov(fit))))
  }
  lapply(seq_along(est), function(i) list(term = names(est)[i], estimate = unname(est[i]), se = unname(se[i])))
}

# The columns of an emmeans summary, whatever emmeans calls them for the model at hand.
interval_columns <- function(s) {
  low <- intersect(c("asymp.LCL", "lower.CL"), names(s))[1]
  high <- intersect(c("asymp.UCL", "upper.CL"), names(s))[1]
  c(low, high)
}

# Estimated marginal means per condition on the response scale with 95 % CIs: probabilities
# (binomial), counts (Poisson, negative binomial), and for clmm the mean answer -- emmeans'
# "mean.class", the expected class number, moved onto the answers' own values where they are
# consecutive whole numbers (otherwise the class number, 1 for the lowest answer given).
marginal_means <- function(fit, engine, answer_levels = NULL) {
  if (engine == "clmm") {
    s <- as.data.frame(summary(emmeans::emmeans(fit, ~ condition, mode = "mean.class")))
    shift <- 0
    values <- suppressWarnings(as.numeric(answer_levels))
    if (!anyNA(values) && all(diff(values) == 1)) shift <- values[1] - 1
  } else {
    s <- as.data.frame(summary(emmeans::emmeans(fit, ~ condition, type = "response")))
    shift <- 0
  }
  ci <- interval_columns(s)
  lapply(seq_len(nrow(s)), function(i) {
    list(condition = as.character(s$condition[i]), estimate = s[[2]][i] + shift, se = s$SE[i],
         low = s[[ci[1]]][i] + shift, high = s[[ci[2]]][i] + shift)
  })
}

# Every pair of conditions (a before b in the levels' order) as a ratio on the response scale:
# exp of the difference on the link (clmm: latent) scale, with its unadjusted 95 % CI and the
# Holm-adjusted p over the model's pairs.
pairwise_ratios <- function(fit, levels) {
  emm <- emmeans::emmeans(fit, ~ condition)
  pairs <- list()
  for (i in seq_along(levels)) for (j in seq_along(levels)) if (i < j) {
    w <- numeric(length(levels))
    w[i] <- 1
    w[j] <- -1
    pairs[[length(pairs) + 1]] <- list(a = levels[i], b = levels[j], w = w)
  }
  if (length(pairs) == 0) return(list())
  method <- setNames(lapply(pairs, `[[`, "w"), paste0("c", seq_along(pairs)))
  con <- emmeans::contrast(emm, method = method)
  ci <- as.data.frame(confint(con, adjust = "none", level = 0.95))
  test <- as.data.frame(emmeans::test(con, adjust = "holm"))
  columns <- interval_columns(ci)
  lapply(seq_along(pairs), function(k) {
    list(a = pairs[[k]]$a, b = pairs[[k]]$b, log_ratio = ci$estimate[k], se = ci$SE[k],
         ratio = exp(ci$estimate[k]), low = exp(ci[[columns[1]]][k]), high = exp(ci[[columns[2]]][k]),
         z = test[[intersect(c("z.ratio", "t.ratio"), names(test))[1]]][k], p_holm = test$p.value[k])
  })
}

# The call that fitted a model, as R code a reader can paste (the data frame named `data`).
call_text <- function(engine, formula) {
  switch(engine,
         binomial = sprintf("lme4::glmer(%s, data, family = binomial(link = \"logit\"))", formula),
         poisson = sprintf("lme4::glmer(%s, data, family = poisson(link = \"log\"))", formula),
         negbin = sprintf("lme4::glmer.nb(%s, data)", formula),
         clmm = sprintf("ordinal::clmm(%s, data, link = \"logit\")", formula))
}

# Everything the report and the JSON say of a kept fit.
summarise_fit <- function(fitted, engine, data, dummies, answer_levels = NULL) {
  fit <- fitted$fit
  levels <- levels(data$condition)
  formula <- paste(deparse(fitted$formula, width.cutoff = 500L), collapse = " ")
  out <- list(engine = engine, call = ENGINES[[engine]]$call, family = ENGINES[[engine]]$family,
              formula = formula, call_text = call_text(engine, formula),
              kept = fitted$step, attempts = fitted$attempts,
              means_scale = ENGINES[[engine]]$scale, ratio = ENGINES[[engine]]$ratio,
              means = marginal_means(fit, engine, answer_levels), contrasts = pairwise_ratios(fit, levels),
              fixed_effects = fixed_effects(fit), random_effects = random_effects(fit, levels, dummies))
  if (engine == "negbin") out$theta <- unname(lme4::getME(fit, "glmer.nb.theta"))
  if (engine == "clmm") {
    out$thresholds <- lapply(names(fit$alpha), function(n) list(term = n, estimate = unname(fit$alpha[[n]])))
  }
  out
}
