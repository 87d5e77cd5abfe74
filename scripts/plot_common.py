"""What the plot scripts share: the command line and how a figure is saved. Imports nothing of
matplotlib, so that a script's helpers stay testable without it."""
import sys


def save(fig, dst):
    """Lays out and writes the figure (PNG at 120 dpi)."""
    fig.tight_layout()
    fig.savefig(dst, dpi=120)


def cli(main, doc, nargs=2):
    """Calls main with the command line's nargs arguments, or exits with the usage (doc)."""
    if len(sys.argv) != nargs + 1:
        sys.exit(doc)
    main(*sys.argv[1:])
