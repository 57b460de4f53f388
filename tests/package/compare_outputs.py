"""Two outputs of the same command from two builds agree: the same words, and numbers equal to
a relative 1e-9 (the builds may round differently in the last bits; printed numbers then match,
or differ in their last printed digit by at most one unit). Elapsed times ("in 0.6 s") are not
compared.

    /usr/bin/python3 tests/package/compare_outputs.py EXPECTED ACTUAL
"""
import re
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
ELAPSED = re.compile(r"\bin [0-9.]+ s\b")


def tokens(line):
    line = ELAPSED.sub("in <time> s", line)
    words, numbers, last = [], [], 0
    for match in NUMBER.finditer(line):
        words.append(line[last:match.start()])
        numbers.append(match.group())
        last = match.end()
    words.append(line[last:])
    return words, numbers


def last_digit_unit(text):
    mantissa = re.split("[eE]", text)[0]
    exponent = int(re.split("[eE]", text)[1]) if re.search("[eE]", text) else 0
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 10.0 ** (exponent - decimals)


def agree(a, b):
    x, y = float(a), float(b)
    if x == y:
        return True
    tolerance = max(1e-9 * max(abs(x), abs(y)), 1.0001 * max(last_digit_unit(a), last_digit_unit(b)))
    return abs(x - y) <= tolerance


def main(expected_path, actual_path):
    with open(expected_path) as f:
        expected = f.read().splitlines()
    with open(actual_path) as f:
        actual = f.read().splitlines()
    problems = []
    if len(expected) != len(actual):
        problems.append(f"{len(expected)} lines against {len(actual)}")
    for number, (e, a) in enumerate(zip(expected, actual), start=1):
        (ew, en), (aw, an) = tokens(e), tokens(a)
        if ew != aw or len(en) != len(an) or not all(agree(x, y) for x, y in zip(en, an)):
            problems.append(f"line {number}:\n  {expected_path}: {e}\n  {actual_path}: {a}")
    if problems:
        print("\n".join(problems[:20]), file=sys.stderr)
        return 1
    print(f"{actual_path} agrees with {expected_path} ({len(actual)} lines)")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
