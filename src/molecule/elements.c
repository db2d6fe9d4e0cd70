/* elements.c: periodic table data and element, mass and radius guesses from names.
 * Masses are IUPAC standard atomic weights (mass number of the longest-lived isotope for
 * elements without one); radii are Bondi's van der Waals radii where he gave one, Mantina's
 * for the main-group elements he did not, and 2.0 A otherwise. */
#include "config.h"
#include "molecule/elements.h"

#include <ctype.h>
#include <string.h>
#include <strings.h>

static const struct {
    const char *sym;
    float mass, radius;
} pte[MS_NUM_ELEMENTS] = {
    {"X", 0.0f, 1.5f},
    {"H", 1.008f, 1.20f},     {"He", 4.0026f, 1.40f},   {"Li", 6.94f, 1.82f},
    {"Be", 9.0122f, 1.53f},   {"B", 10.81f, 1.92f},     {"C", 12.011f, 1.70f},
    {"N", 14.007f, 1.55f},    {"O", 15.999f, 1.52f},    {"F", 18.998f, 1.47f},
    {"Ne", 20.180f, 1.54f},   {"Na", 22.990f, 2.27f},   {"Mg", 24.305f, 1.73f},
    {"Al", 26.982f, 1.84f},   {"Si", 28.085f, 2.10f},   {"P", 30.974f, 1.80f},
    {"S", 32.06f, 1.80f},     {"Cl", 35.45f, 1.75f},    {"Ar", 39.948f, 1.88f},
    {"K", 39.098f, 2.75f},    {"Ca", 40.078f, 2.31f},   {"Sc", 44.956f, 2.11f},
    {"Ti", 47.867f, 2.0f},    {"V", 50.942f, 2.0f},     {"Cr", 51.996f, 2.0f},
    {"Mn", 54.938f, 2.0f},    {"Fe", 55.845f, 2.0f},    {"Co", 58.933f, 2.0f},
    {"Ni", 58.693f, 1.63f},   {"Cu", 63.546f, 1.40f},   {"Zn", 65.38f, 1.39f},
    {"Ga", 69.723f, 1.87f},   {"Ge", 72.630f, 2.11f},   {"As", 74.922f, 1.85f},
    {"Se", 78.971f, 1.90f},   {"Br", 79.904f, 1.85f},   {"Kr", 83.798f, 2.02f},
    {"Rb", 85.468f, 3.03f},   {"Sr", 87.62f, 2.49f},    {"Y", 88.906f, 2.0f},
    {"Zr", 91.224f, 2.0f},    {"Nb", 92.906f, 2.0f},    {"Mo", 95.95f, 2.0f},
    {"Tc", 98.0f, 2.0f},      {"Ru", 101.07f, 2.0f},    {"Rh", 102.91f, 2.0f},
    {"Pd", 106.42f, 1.63f},   {"Ag", 107.87f, 1.72f},   {"Cd", 112.41f, 1.58f},
    {"In", 114.82f, 1.93f},   {"Sn", 118.71f, 2.17f},   {"Sb", 121.76f, 2.06f},
    {"Te", 127.60f, 2.06f},   {"I", 126.90f, 1.98f},    {"Xe", 131.29f, 2.16f},
    {"Cs", 132.91f, 3.43f},   {"Ba", 137.33f, 2.68f},   {"La", 138.91f, 2.0f},
    {"Ce", 140.12f, 2.0f},    {"Pr", 140.91f, 2.0f},    {"Nd", 144.24f, 2.0f},
    {"Pm", 145.0f, 2.0f},     {"Sm", 150.36f, 2.0f},    {"Eu", 151.96f, 2.0f},
    {"Gd", 157.25f, 2.0f},    {"Tb", 158.93f, 2.0f},    {"Dy", 162.50f, 2.0f},
    {"Ho", 164.93f, 2.0f},    {"Er", 167.26f, 2.0f},    {"Tm", 168.93f, 2.0f},
    {"Yb", 173.05f, 2.0f},    {"Lu", 174.97f, 2.0f},    {"Hf", 178.49f, 2.0f},
    {"Ta", 180.95f, 2.0f},    {"W", 183.84f, 2.0f},     {"Re", 186.21f, 2.0f},
    {"Os", 190.23f, 2.0f},    {"Ir", 192.22f, 2.0f},    {"Pt", 195.08f, 1.75f},
    {"Au", 196.97f, 1.66f},   {"Hg", 200.59f, 1.55f},   {"Tl", 204.38f, 1.96f},
    {"Pb", 207.2f, 2.02f},    {"Bi", 208.98f, 2.07f},   {"Po", 209.0f, 1.97f},
    {"At", 210.0f, 2.02f},    {"Rn", 222.0f, 2.20f},    {"Fr", 223.0f, 3.48f},
    {"Ra", 226.0f, 2.83f},    {"Ac", 227.0f, 2.0f},     {"Th", 232.04f, 2.0f},
    {"Pa", 231.04f, 2.0f},    {"U", 238.03f, 1.86f},    {"Np", 237.0f, 2.0f},
    {"Pu", 244.0f, 2.0f},     {"Am", 243.0f, 2.0f},     {"Cm", 247.0f, 2.0f},
    {"Bk", 247.0f, 2.0f},     {"Cf", 251.0f, 2.0f},     {"Es", 252.0f, 2.0f},
    {"Fm", 257.0f, 2.0f},     {"Md", 258.0f, 2.0f},     {"No", 259.0f, 2.0f},
    {"Lr", 262.0f, 2.0f},     {"Rf", 267.0f, 2.0f},     {"Db", 268.0f, 2.0f},
    {"Sg", 271.0f, 2.0f},     {"Bh", 272.0f, 2.0f},     {"Hs", 270.0f, 2.0f},
    {"Mt", 276.0f, 2.0f},     {"Ds", 281.0f, 2.0f},     {"Rg", 280.0f, 2.0f},
    {"Cn", 285.0f, 2.0f},     {"Nh", 284.0f, 2.0f},     {"Fl", 289.0f, 2.0f},
    {"Mc", 288.0f, 2.0f},     {"Lv", 293.0f, 2.0f},     {"Ts", 294.0f, 2.0f},
    {"Og", 294.0f, 2.0f},
};

const char *ms_element_symbol(int z)
{
    return (z > 0 && z < MS_NUM_ELEMENTS) ? pte[z].sym : "X";
}

float ms_element_mass(int z)
{
    return (z > 0 && z < MS_NUM_ELEMENTS) ? pte[z].mass : 0.0f;
}

float ms_element_vdw_radius(int z)
{
    return (z > 0 && z < MS_NUM_ELEMENTS) ? pte[z].radius : 1.5f;
}

/* Atomic number of a one- or two-letter symbol given as separate characters. */
static int symbol_lookup(char c0, char c1)
{
    c0 = (char)toupper((unsigned char)c0);
    c1 = (char)tolower((unsigned char)c1);
    for (int z = 1; z < MS_NUM_ELEMENTS; z++) {
        const char *s = pte[z].sym;
        if (s[0] == c0 && s[1] == c1) return z;
    }
    return 0;
}

int ms_element_from_symbol(const char *sym)
{
    while (*sym == ' ') sym++;
    size_t n = strlen(sym);
    while (n && sym[n - 1] == ' ') n--;
    if (n == 0 || n > 2 || !isalpha((unsigned char)sym[0])) return 0;
    if (n == 2 && !isalpha((unsigned char)sym[1])) return 0;
    return symbol_lookup(sym[0], n == 2 ? sym[1] : '\0');
}

int ms_element_guess(const char *name, const char *resname)
{
    while (isdigit((unsigned char)*name)) name++;
    if (!isalpha((unsigned char)name[0])) return 0;
    char c0 = name[0], c1 = isalpha((unsigned char)name[1]) ? name[1] : '\0';
    /* An ion or lone atom named like its residue: NA in NA, CL in CL, ZN in ZN. */
    if (c1 && resname && strcasecmp(name, resname) == 0 && name[2] == '\0') {
        int z = symbol_lookup(c0, c1);
        if (z) return z;
    }
    /* CHARMM's single-atom ion residues. */
    static const struct { const char *res; int z; } ions[] = {
        {"SOD", 11}, {"POT", 19}, {"CLA", 17}, {"CAL", 20}, {"CES", 55}, {"LIT", 3},
        {"RUB", 37}, {"BAR", 56}, {"ZN2", 30}, {"MG2", 12}};
    if (resname && strcasecmp(name, resname) == 0)
        for (size_t k = 0; k < sizeof ions / sizeof ions[0]; k++)
            if (strcasecmp(resname, ions[k].res) == 0) return ions[k].z;
    int z = symbol_lookup(c0, '\0');
    if (z) return z;
    return c1 ? symbol_lookup(c0, c1) : 0;
}

float ms_element_radius_from_name(const char *name)
{
    while (isdigit((unsigned char)*name)) name++;
    switch (toupper((unsigned char)name[0])) {
    case 'H': return 1.0f;
    case 'C': return 1.5f;
    case 'N': return 1.4f;
    case 'O': return 1.3f;
    case 'F': return 1.2f;
    case 'S': return 1.9f;
    default: return 1.5f;
    }
}
