"""Count the steps of a chains file that are the user's first use of that exact action."""

import sys

from oracle.evaluation.replay import load_users

users = load_users(sys.argv[1])
total = first = 0
for rows in users.values():
    seen = set()
    for row in rows:
        total += 1
        first += row.action not in seen
        seen.add(row.action)
print(f"{first} of {total} steps ({100 * first / total:.1f} %) are a first use")
