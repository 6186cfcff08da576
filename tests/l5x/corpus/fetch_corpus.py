"""Rebuild the real-export corpus described by manifest.toml.

    python tests/l5x/corpus/fetch_corpus.py [--mirror-root DIR] [--dest DIR] [--cache DIR]

Every [[file]] of manifest.toml names a public GitHub repository, a commit and a path. This
script writes the bytes of `git show COMMIT:PATH` to DEST/<file> and checks their sha256
against the manifest (a mismatch is reported and the file is not kept). DEST is --dest, else
$LOGIXST_L5X_CORPUS, else /work/l5x-corpus.

Where the bytes come from, for each repository in turn:
- --mirror-root DIR: a bare git directory DIR/<owner>+<name>/repo (or .../repo/.git), as the
  development machine keeps its local mirrors;
- otherwise a blob-less `git clone --filter=blob:none --no-checkout` of
  https://github.com/<owner>/<name> into --cache (default ~/.cache/logixst-l5x-corpus), so
  only the blobs asked for are downloaded. This needs network access and git >= 2.19.

Files already present with the right sha256 are left alone. The exit status is 0 when every
file of the manifest is in DEST with the right sha256, 1 otherwise. The test suite never runs
this script: tests/l5x/test_corpus.py skips the files that are absent and names this script
in its skip reason.

The exports stay on the machine that fetched them: they are not ours to redistribute (most of
their repositories carry no licence), which is why only the manifest is committed.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import subprocess
import sys
import tomllib
from pathlib import Path

MANIFEST = Path(__file__).with_name("manifest.toml")
DEFAULT_DEST = Path(os.environ.get("LOGIXST_L5X_CORPUS", "/work/l5x-corpus"))
DEFAULT_CACHE = Path.home() / ".cache" / "logixst-l5x-corpus"


def load_manifest(path: Path = MANIFEST) -> list[dict[str, object]]:
    entries: list[dict[str, object]] = tomllib.loads(path.read_text(encoding="utf-8"))["file"]
    return entries


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def mirror_gitdir(root: Path, repo: str) -> Path | None:
    """The bare git directory of `repo` under a mirror root, or None."""
    base = root / repo.replace("/", "+") / "repo"
    for candidate in (base / ".git", base):
        if (candidate / "objects").is_dir():
            return candidate
    return None


def clone_gitdir(cache: Path, repo: str, remote_base: str = "https://github.com/") -> Path:
    """A blob-less bare clone of <remote_base><repo>.git in the cache (made once)."""
    target = cache / repo.replace("/", "+")
    if not (target / "objects").is_dir():
        cache.mkdir(parents=True, exist_ok=True)
        subprocess.run(
            [
                "git",
                "clone",
                "--bare",
                "--filter=blob:none",
                f"{remote_base}{repo}.git",
                str(target),
            ],
            check=True,
        )
    return target


def git_show(gitdir: Path, commit: str, path: str) -> bytes | None:
    proc = subprocess.run(
        ["git", "--git-dir", str(gitdir), "show", f"{commit}:{path}"],
        capture_output=True,
    )
    return proc.stdout if proc.returncode == 0 else None


def fetch_missing_commit(gitdir: Path, commit: str) -> None:
    """A clone may lack a commit that was later rewritten away; ask the remote for it."""
    subprocess.run(
        ["git", "--git-dir", str(gitdir), "fetch", "--filter=blob:none", "origin", commit],
        capture_output=True,
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description="Rebuild the real-export corpus from manifest.toml.")
    ap.add_argument("--mirror-root", type=Path, help="directory of local bare git mirrors")
    ap.add_argument("--dest", type=Path, default=DEFAULT_DEST)
    ap.add_argument("--cache", type=Path, default=DEFAULT_CACHE, help="where clones are kept")
    ap.add_argument("--manifest", type=Path, default=MANIFEST)
    ap.add_argument(
        "--remote-base",
        default="https://github.com/",
        help="where clones come from: <base><owner>/<name>.git (default GitHub)",
    )
    args = ap.parse_args(argv)

    args.dest.mkdir(parents=True, exist_ok=True)
    gitdirs: dict[str, Path | None] = {}
    ok = missing = bad = 0
    for e in load_manifest(args.manifest):
        name, repo = str(e["file"]), str(e["repo"])
        commit, path, want = str(e["commit"]), str(e["path"]), str(e["sha256"])
        out = args.dest / name
        if out.is_file() and sha256(out.read_bytes()) == want:
            ok += 1
            continue
        if repo not in gitdirs:
            gitdir = mirror_gitdir(args.mirror_root, repo) if args.mirror_root else None
            if gitdir is None:
                try:
                    gitdir = clone_gitdir(args.cache, repo, args.remote_base)
                except (subprocess.CalledProcessError, OSError) as exc:
                    print(f"{repo}: cannot clone ({exc})", file=sys.stderr)
                    gitdir = None
            gitdirs[repo] = gitdir
        gitdir = gitdirs[repo]
        data = None
        if gitdir is not None:
            data = git_show(gitdir, commit, path)
            if data is None and not args.mirror_root:
                fetch_missing_commit(gitdir, commit)
                data = git_show(gitdir, commit, path)
        if data is None:
            print(f"{name}: not found ({repo} {commit[:12]}:{path})", file=sys.stderr)
            missing += 1
            continue
        if sha256(data) != want:
            print(f"{name}: sha256 differs from the manifest, not written", file=sys.stderr)
            bad += 1
            continue
        out.write_bytes(data)
        ok += 1
    print(f"{ok} files in {args.dest}, {missing} not found, {bad} with a wrong sha256")
    return 0 if missing == bad == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
