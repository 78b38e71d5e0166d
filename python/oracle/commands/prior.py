"""``python -m oracle share`` and ``python -m oracle prior build|show``: consent, and the shared prior
counted over the consenting NEEMs of a store (docs/algorithm.md, "Shared prior")."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from oracle.commands.common import JSON, NEEM, ONTOLOGY_OPTIONS, STORE, add_options


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    share = subparsers.add_parser("share", help="let a NEEM's aggregates enter a shared prior (or --revoke that)",
                                  description="Records in the NEEM's registry entry that its counts of task contexts "
                                  "may enter the priors 'prior build' makes; nothing is shared by default. --revoke "
                                  "withdraws it: the next prior built holds none of the NEEM's counts.")
    add_options(share, STORE, NEEM)
    share.add_argument("--revoke", action="store_true", help="withdraw the consent")
    share.set_defaults(handler=run_share)

    prior = subparsers.add_parser("prior", help="build or show a shared prior of what people usually do next")
    actions = prior.add_subparsers(dest="action", required=True, metavar="{build,show}")
    build = actions.add_parser("build", help="count task contexts over the store's consenting NEEMs")
    add_options(build, STORE, *ONTOLOGY_OPTIONS)
    build.add_argument("--k", type=int, default=5, help="keep a count only when >= K users gave it (default 5)")
    build.add_argument("--epsilon", type=float, default=None,
                       help="add Laplace noise: each count epsilon-differentially private (default: no noise)")
    build.add_argument("--clip", type=int, default=3, help="at most this much of each count from one user (default 3)")
    build.add_argument("--out", type=Path, required=True, metavar="PRIOR.json")
    build.set_defaults(handler=run_build)
    show = actions.add_parser("show", help="print what a prior file holds")
    show.add_argument("file", type=Path, metavar="PRIOR.json")
    show.add_argument("--top", type=int, default=5, help="the largest counts to list per order (default 5)")
    add_options(show, JSON)
    show.set_defaults(handler=run_show)


def run_share(args: argparse.Namespace) -> int:
    from oracle.neem.sharing import set_shared
    from oracle.store import open_store
    from oracle.store.ids import resolve_neem

    with open_store(args.store, create=False) as store:
        if args.neem is None:
            from oracle.errors import StoreError

            raise StoreError("share: give the NEEM with --neem ID")
        neem = resolve_neem(store, args.neem)
        set_shared(store, neem, not args.revoke)
    print(f"NEEM {neem}: {'not shared (consent withdrawn)' if args.revoke else 'its aggregates may enter a prior'}")
    return 0


def run_build(args: argparse.Namespace) -> int:
    from oracle.algorithm.prior_counts import check_privacy
    from oracle.commands.common import ontology_from
    from oracle.errors import StoreError
    from oracle.neem.sharing import build_prior, shared_neems
    from oracle.ontology.provenance import Recorded, fingerprint
    from oracle.store import open_store

    check_privacy(args.k, args.epsilon, args.clip)  # before anything is read
    ontology = ontology_from(args)
    mark = fingerprint(ontology)
    with open_store(args.store, create=False, read_only=True) as store:
        neems = shared_neems(store)
        for info in neems:
            recorded = Recorded.from_meta(info.meta)
            if recorded is not None and recorded.fingerprint != mark:
                raise StoreError(f"NEEM {info.id} was logged under another ontology (fingerprint "
                                 f"{recorded.fingerprint}, given {mark}): give its --odb/--mapping or --ontology")
        prior = build_prior(store, ontology, args.k, args.epsilon, args.clip, None, neems)
    prior.save(args.out)
    noise = f", Laplace noise of scale {args.clip / args.epsilon:g} per count" if args.epsilon is not None else ""
    print(f"{args.out}: {prior.cells()} counts in {prior.contexts()} contexts from {len(neems)} shared NEEMs of "
          f"{prior.users} users (k {args.k}, clip {args.clip}{noise})")
    return 0


def run_show(args: argparse.Namespace) -> int:
    from oracle.algorithm.prior import load_prior
    from oracle.neem.sharing import describe

    prior = load_prior(args.file)
    found = describe(prior)
    if args.json:
        found["orders"] = {str(n): [{"count": c, "context": list(ctx), "next": t} for c, ctx, t in rows[:args.top]]
                           for n, rows in found["orders"].items()}
        print(json.dumps(found, indent=1))
        return 0
    eps = "none" if prior.epsilon is None else f"{prior.epsilon:g}"
    print(f"prior of {prior.users} users, ontology {prior.fingerprint}: {found['counts']} counts in "
          f"{found['contexts']} contexts; k {prior.k}, clip {prior.clip}, epsilon {eps}")
    for n, rows in found["orders"].items():
        print(f"order {n}: {len(rows)} counts")
        for count, context, task in rows[:args.top]:
            after = " after " + " ".join(context) if context else ""
            print(f"  {count:10.1f}  {task}{after}")
    return 0
