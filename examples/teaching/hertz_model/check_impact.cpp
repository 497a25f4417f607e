// Reads the history.csv of examples/teaching/impact_speeds.json run with the
// `hertz` model in plab, and compares each ball's contact time (the steps
// with a non-zero force on it) with Hertz's 2.868 (m*^2/(R* E*^2 v))^(1/5).
//   check_impact HISTORY.csv E nu      exit 0 when all three are within 2 %
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 4) { std::fprintf(stderr, "usage: check_impact HISTORY.csv E nu\n"); return 2; }
    const double E = std::atof(argv[2]), nu = std::atof(argv[3]);
    const double E_eff = E / (2 * (1 - nu * nu)), R = 0.005, m = 2500 * 4.0 / 3.0 * M_PI * R * R * R;  // as in the scene
    const double speeds[3] = {0.2, 1.0, 5.0};
    std::ifstream f(argv[1]);
    std::string line;
    std::getline(f, line);  // time, force_0.2, force_1, force_5
    std::vector<std::vector<double>> rows;
    while (std::getline(f, line)) {
        std::stringstream s(line);
        std::vector<double> row;
        for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::atof(cell.c_str()));
        if (row.size() == 4) rows.push_back(row);
    }
    if (rows.size() < 3) { std::fprintf(stderr, "%s: no history rows\n", argv[1]); return 2; }
    const double dt = rows[2][0] - rows[1][0];
    int failed = 0;
    for (int b = 0; b < 3; ++b) {
        long steps = 0;
        for (const auto& r : rows) steps += r[1 + b] != 0.0;
        const double t = steps * dt, exact = 2.868 * std::pow(m * m / (R * E_eff * E_eff * speeds[b]), 0.2);
        const double err = t / exact - 1;
        std::printf("v = %.1f m/s: contact time in plab %.4e s, Hertz %.4e s, error %+.2f %% (step %.1e s)\n", speeds[b], t,
                    exact, 100 * err, dt);
        failed += std::fabs(err) > 0.02;
    }
    return failed ? 1 : 0;
}
