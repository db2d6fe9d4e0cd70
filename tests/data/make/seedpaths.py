"""seedpaths.py: what make_seeds.py and make_seeds2.py share: warnings silenced, the paths of
tests/data (DATA) and of the fuzz seed corpora (CORPUS), and out(fmt, name), the path of a
seed in tests/fuzz/corpus/<fmt>/ (the folder made when missing)."""
import os
import warnings

warnings.simplefilter("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)
CORPUS = os.path.join(os.path.dirname(DATA), "fuzz", "corpus")


def out(fmt, name):
    d = os.path.join(CORPUS, fmt)
    os.makedirs(d, exist_ok=True)
    return os.path.join(d, name)
