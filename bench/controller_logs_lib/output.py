"""Prints the report as plain text or markdown: titles, paragraphs, bullets, tables, and the
formatting of numbers in them."""

import re
import statistics


# ----------------------------------------------------------------------------------------
# Output: plain text or markdown tables.

class Out:
    def __init__(self, markdown):
        self.md = markdown

    def title(self, text, level=2):
        if self.md:
            print('\n' + '#' * level + ' ' + text + '\n')
        else:
            print('\n' + text + '\n' + ('=' if level <= 2 else '-') * len(text))

    def para(self, text):
        print(text if self.md else text)
        print()

    def bullets(self, items):
        for it in items:
            print('- ' + it)
        print()

    def table(self, head, rows):
        rows = [[cell(c) for c in r] for r in rows]
        if self.md:
            head = [h.replace('|', '\\|') for h in head]
            rows = [[c.replace('|', '\\|') for c in r] for r in rows]
            print('| ' + ' | '.join(head) + ' |')
            print('|' + '|'.join('---' for _ in head) + '|')
            for r in rows:
                print('| ' + ' | '.join(r) + ' |')
        else:
            w = [max([len(h)] + [len(r[i]) for r in rows]) for i, h in enumerate(head)]
            print('  '.join(h.ljust(w[i]) for i, h in enumerate(head)))
            print('  '.join('-' * w[i] for i in range(len(head))))
            for r in rows:
                print('  '.join(c.rjust(w[i]) if looks_numeric(c) else c.ljust(w[i])
                                for i, c in enumerate(r)))
        print()


def cell(c):
    if c is None:
        return '-'
    if isinstance(c, float):
        return '%.2f' % c
    return str(c)


def looks_numeric(s):
    return bool(re.match(r'^[-+]?[\d.]+(%| s)?$', s))


def pct(x):
    return '-' if x is None else '%+.1f%%' % (100 * x)


def upct(x):
    return '-' if x is None else '%.1f%%' % (100 * x)


def spread(xs):
    """(min, median, max) as text."""
    xs = [x for x in xs if x is not None]
    if not xs:
        return '-'
    return '%.1f / %.1f / %.1f' % (min(xs), statistics.median(xs), max(xs))
