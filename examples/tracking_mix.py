#!/usr/bin/env python3
"""Offline study of the tracking mixture's weighting (Python 3, standard library only).

Reads what `cargo run --release --example tracking_members -- target/members` wrote (every
prediction the assimilated bank scored, as each member made it) and compares rules for mixing
the members on exactly the same predictions, in seconds instead of the tracking table's
minutes. The first row reproduces the mixture as kept (within 0.003 of the table's means over
the wells, 0.007 per well); the others are the variants of docs/tracking.md's "Measured and not kept".

Run: `python3 examples/tracking_mix.py [target/members]`.

The direction error of a correction c is |z - c| (z the observed correction, small angles:
within 0.05 deg/100 m of the table's means), per 100 m; the references' errors are the
table's exact ones. Ratios: the mixture's mean error over the best naive projection's (hold,
rates 30/60/90 m, the best chosen per well after the fact) and over the statistic's, per well,
then their mean and worst over the four real wells.
"""
import itertools
import json
import math
import sys

DIR = sys.argv[1] if len(sys.argv) > 1 else 'target/members'
WELLS = ['forge-16a', 'forge-16b', 'volve-f10', 'volve-f5']
DEG = math.pi / 180
PRIOR_VAR = (1 * DEG / 30) ** 2  # [tracking] fluctuation_sd squared, (rad/m)^2
FLOOR = PRIOR_VAR * 0.05 ** 2    # MIN_FLUCTUATION_FRACTION of it
FORGET = 300.0                   # [tracking] forgetting_length, m
CORRELATION = 30.0               # [tracking] correlation_length, m


def load(well, h):
    d = json.load(open(f'{DIR}/{well}_{h}m.json'))
    first = d['intervals'][0]['from_md']
    for e in d['events']:
        e['is_iv'] = e['from_md'] >= first - 1e-6
    return d


def log_lik(y, c):
    a, b, dd = c
    det = a * dd - b * b
    if det <= 0:
        return 0.0
    return -0.5 * ((dd * y[0] ** 2 - 2 * b * y[0] * y[1] + a * y[1] ** 2) / det + math.log(det))


def mixture(ws, preds):
    m = [sum(w * p[0][c] for w, p in zip(ws, preds)) for c in (0, 1)]
    cov = [0.0, 0.0, 0.0]
    for w, (t, cv) in zip(ws, preds):
        d0, d1 = t[0] - m[0], t[1] - m[1]
        cov[0] += w * (cv[0] + d0 * d0)
        cov[1] += w * (cv[1] + d0 * d1)
        cov[2] += w * (cv[2] + d1 * d1)
    return m, cov


def softmax(s):
    t = max(s)
    w = [math.exp(x - t) for x in s]
    return [x / sum(w) for x in w]


def change(a, b):
    """The turn (toward the high side, toward the right) from direction a to b, small angles."""
    dazi = (b[1] - a[1] + math.pi) % (2 * math.pi) - math.pi
    return [b[0] - a[0], math.sin(0.5 * (a[0] + b[0])) * dazi]


class Adaptive:
    """A naive member whose covariance is its adapted past error variance, as NaiveMembers."""

    def __init__(self, corr):
        self.corr, self.sw, self.pw, self.si = corr, 0.0, 1.0, [0.0, 0.0]

    def __call__(self, e):
        L, t, es = e['len'], self.corr(e), e['end_station']
        v = [max((self.pw * PRIOR_VAR + self.si[c]) / (self.pw + self.sw), FLOOR) * L * L for c in (0, 1)]
        return t, [v[0] + es[0], es[1], v[1] + es[2]]

    def update(self, e, t):
        L, es = e['len'], e['end_station']
        keep = math.exp(-L / FORGET)
        self.sw, self.pw = self.sw * keep + 1, self.pw * keep
        for c, r in ((0, es[0]), (1, es[2])):
            self.si[c] = self.si[c] * keep + max((e['z'][c] - t[c]) ** 2 - r, 0) / (L * L)


# ---- members: each a factory of a callable e -> (correction, covariance) -----------------------
def bank():
    return lambda e: mixture(e['filter_weights'], e['filters'])


def naive(k):
    return lambda: Adaptive(lambda e: e['naive'][k][0])


def ou(ell_fn):
    """Hold plus the last 30 m's rate decaying over a correlation length: r l (1 - exp(-h/l))."""
    def corr(e):
        r = change(e['behind'][3], e['behind'][0])
        ell = ell_fn(e)
        g = ell * (1 - math.exp(-e['len'] / ell)) / 30
        return [e['naive'][2][0][c] + r[c] * g for c in (0, 1)]
    return lambda: Adaptive(corr)


def ell_estimated(e):
    """Correlation length of the 30 m rates of the 300 m behind (lag-one autocorrelation)."""
    b = e['behind']
    rates = [change(b[i + 3], b[i]) for i in range(0, 28, 3)]
    num = sum(rates[i][c] * rates[i + 1][c] for c in (0, 1) for i in range(len(rates) - 1))
    den = sum(r[c] ** 2 for c in (0, 1) for r in rates)
    rho = num / den if den > 0 else 0.0
    return min(300.0, max(5.0, -30 / math.log(rho))) if 0.01 < rho < 0.99 else (5.0 if rho <= 0.01 else 300.0)


def ar1(n_rates=5):
    """AR(1) of the 30 m rates (mean 0) fitted on the last n_rates behind, its forecast summed."""
    def corr(e):
        b = e['behind']
        rates = [change(b[i + 3], b[i]) for i in range(0, 3 * n_rates, 3)]
        out = list(e['naive'][2][0])
        for c in (0, 1):
            x = [r[c] / 30 for r in rates]
            den = sum(v * v for v in x)
            phi = min(0.98, max(0.0, sum(x[i] * x[i + 1] for i in range(len(x) - 1)) / den if den > 0 else 0.0))
            ell = -30 / math.log(phi) if phi > 1e-6 else 1e-6
            out[c] += x[0] * ell * (1 - math.exp(-e['len'] / ell))
        return out
    return lambda: Adaptive(corr)


KEPT = [bank, naive(0), naive(1), naive(2)]  # the filters as one member, no correction, statistic, hold
HOLD = 3


def hold_share(h, ell):
    """The share of hold in a prior by the rates' persistence: 1 - l (1 - exp(-h/l)) / h."""
    return 1 - ell * (1 - math.exp(-h / ell)) / h


# ---- rules: each maps a run's events to the corrections of its intervals -------------------------
def likelihood(members=KEPT, temper=1.0, warm=True, forget=FORGET, hold_prior=None):
    def rule(evs):
        ms = [m() for m in members]
        s, out = [0.0] * len(ms), []
        for e in evs:
            preds = [m(e) for m in ms]
            prior = [0.0] * len(ms)
            if hold_prior is not None:
                p = hold_share(e['len'], hold_prior)
                prior = [math.log((1 - p) / (len(ms) - 1))] * len(ms)
                prior[HOLD] = math.log(p)
            w = softmax([temper * x + q for x, q in zip(s, prior)])
            if e['is_iv']:
                out.append(mixture(w, preds)[0])
            if e['is_iv'] or warm:
                keep = math.exp(-e['len'] / forget)
                for k, p in enumerate(preds):
                    s[k] = s[k] * keep + log_lik([e['z'][0] - p[0][0], e['z'][1] - p[0][1]], p[1])
            for m, p in zip(ms, preds):
                if isinstance(m, Adaptive):
                    m.update(e, p[0])
        return out
    return rule


def inverse_mse(members=KEPT, power=1.0):
    """Bates-Granger: weights as the inverse forgetting-weighted mean square error, to a power."""
    def rule(evs):
        ms = [m() for m in members]
        s, n, out = [0.0] * len(ms), 0.0, []
        for e in evs:
            preds = [m(e) for m in ms]
            w = [1.0] * len(ms) if n == 0 else [(x / n + 1e-30) ** -power for x in s]
            w = [x / sum(w) for x in w]
            if e['is_iv']:
                out.append([sum(wk * p[0][c] for wk, p in zip(w, preds)) for c in (0, 1)])
            keep = math.exp(-e['len'] / FORGET)
            n = n * keep + 1
            for k, p in enumerate(preds):
                s[k] = s[k] * keep + (e['z'][0] - p[0][0]) ** 2 + (e['z'][1] - p[0][1]) ** 2
            for m, p in zip(ms, preds):
                if isinstance(m, Adaptive):
                    m.update(e, p[0])
        return out
    return rule


def fixed(weights, members=KEPT):
    """Fixed weights on every interval (an after-the-fact bound, not a predictor)."""
    def rule(evs):
        ms = [m() for m in members]
        return [mixture(weights, [m(e) for m in ms])[0] for e in evs if e['is_iv']]
    return rule


# ---- evaluation ---------------------------------------------------------------------------------
CACHE = {}


def ratios(rule, h):
    out = []
    for w in WELLS:
        d = CACHE.setdefault((w, h), load(w, h))
        corr = rule(d['events'])
        ivs = [e for e in d['events'] if e['is_iv']]
        assert len(ivs) == len(corr) == len(d['ends'])
        mean = sum(math.hypot(e['z'][0] - c[0], e['z'][1] - c[1]) / e['len'] for e, c in zip(ivs, corr)) / len(ivs)

        def ref(k):
            def ang(p, m):
                ta = (math.sin(p[0]) * math.cos(p[1]), math.sin(p[0]) * math.sin(p[1]), math.cos(p[0]))
                tb = (math.sin(m[0]) * math.cos(m[1]), math.sin(m[0]) * math.sin(m[1]), math.cos(m[0]))
                dot = sum(x * y for x, y in zip(ta, tb))
                return math.atan2(math.sqrt(max(0.0, 1 - dot * dot)), dot)
            return sum(ang(x['references'][k], x['measured']) / x['len'] for x in d['ends']) / len(d['ends'])
        out.append((mean / min(ref(k) for k in range(4)), mean / ref(4)))
    return out


def first_replaced(weights):
    """The mixture as kept, its first interval's correction replaced by fixed weights' (a bound)."""
    kept = likelihood()

    def rule(evs):
        ms = [m() for m in KEPT]
        first = next(e for e in evs if e['is_iv'])
        return [mixture(weights, [m(first) for m in ms])[0]] + kept(evs)[1:]
    return rule


def row(name, rule):
    cells = []
    for h in (30, 90):
        r = ratios(rule, h)
        best = [x[0] for x in r]
        cells.append(f'{sum(best) / 4:.3f} / {max(best):.3f} / {sum(x[1] for x in r) / 4:.3f}'
                     f' [{" ".join(f"{x:.2f}" for x in best)}]')
    print(f'| {name} | {cells[0]} | {cells[1]} |')


if __name__ == '__main__':
    print('| rule | 30 m: mean / worst / vs statistic [per well] | 90 m: the same |')
    print('|---|---|---|')
    row('as kept (likelihood, warm-up scored)', likelihood())
    row('no warm-up scoring', likelihood(warm=False))
    row('tempered likelihood x0.5', likelihood(temper=0.5))
    row('tempered x0.5, no warm-up scoring', likelihood(temper=0.5, warm=False))
    for f in (150, 600):
        row(f'weights forgotten over {f} m', likelihood(forget=f))
    row('inverse mean square error (Bates-Granger)', inverse_mse())
    row('inverse mean square error squared', inverse_mse(power=2))
    row('+ member: hold + 30 m rate decaying over l estimated behind', likelihood(KEPT + [ou(ell_estimated)]))
    row('statistic -> rate decaying over 30 m', likelihood([bank, naive(0), ou(lambda e: 30.0), naive(2)]))
    row('+ member: AR(1) of the last five 30 m rates', likelihood(KEPT + [ar1()]))
    for ell in (20.0, 30.0, 40.0):
        row(f'hold prior 1 - l(1 - exp(-h/l))/h, l = {ell:.0f} m', likelihood(hold_prior=ell))
        row(f'the same, no warm-up scoring, l = {ell:.0f} m', likelihood(hold_prior=ell, warm=False))
    for ell in (30.0, 20.0):
        row(f'+ AR(1) member and the hold prior, l = {ell:.0f} m', likelihood(KEPT + [ar1()], hold_prior=ell))
    # after-the-fact bounds: fixed weights on the 90 m intervals (grid of 0.1), chosen on the results
    results = []
    for a, b, s in itertools.product([i / 10 for i in range(11)], repeat=3):
        if a + b + s <= 1 + 1e-9:
            w = [a, b, s, round(1 - a - b - s, 1)]
            r = [x[0] for x in ratios(fixed(w), 90)]
            results.append((sum(r) / 4, max(r), w))
    print('\nfixed weights at 90 m chosen after the fact (bank, no correction, statistic, hold):')
    for mean, worst, w in sorted(results, key=lambda x: x[1])[:3]:
        print(f'  least worst: {w}: mean {mean:.3f}, worst {worst:.3f}')
    for mean, worst, w in sorted([r for r in results if r[1] <= 1.1])[:3]:
        print(f'  least mean with worst <= 1.10: {w}: mean {mean:.3f}, worst {worst:.3f}')
    best = min((max(x[0] for x in ratios(first_replaced(w), 90)), w) for _, _, w in results)
    print(f'  the mixture as kept, only its first 90 m interval mixed by fixed weights: least worst'
          f' {best[0]:.3f} with {best[1]}')
