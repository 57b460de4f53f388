function test_spdfit_mex()
% The MATLAB/Octave interface against the command-line tool on the same data, its input types,
% warning and error identifiers, help text, memory across calls and what the MEX links. Run by
% CTest under Octave (matlab/CMakeLists.txt) with SPDFIT_CLI and SPDFIT_MEX set.
cli = getenv('SPDFIT_CLI');
assert(~isempty(cli), 'SPDFIT_CLI is not set');
work = tempname();
mkdir(work);
cleanup = onCleanup(@() remove_folder(work));
[A, B] = sample_data();
write_csv(fullfile(work, 'A.csv'), A);
write_csv(fullfile(work, 'B.csv'), B);

methods = {'ls', 'procrustes', 'tls', 'tls-sym', 'tls-psd', 'spde', 'spd-tls', 'psd-ls', 'auto'};
for k = 1:numel(methods)
  [X, info] = spdfit.fit(A, B, methods{k});
  ref = cli_json(cli, sprintf('fit --method %s --json "%s" "%s"', methods{k}, fullfile(work, 'A.csv'), ...
                              fullfile(work, 'B.csv')));
  assert_close(X, ref.X, 1e-13, ['fit ' methods{k}]);
  assert_same_fields(info, ref, ['fit ' methods{k}]);
end

% The bootstrap: the same replicates as the CLI's (one generator per replicate, keyed by the seed).
[X, info] = spdfit.fit(A, B, 'spd-tls', 'Bootstrap', 50, 'Seed', 3, 'Confidence', 0.9);
ref = cli_json(cli, sprintf('fit --method spd-tls --bootstrap 50 --seed 3 --confidence 0.9 --json "%s" "%s"', ...
                            fullfile(work, 'A.csv'), fullfile(work, 'B.csv')));
assert_close(X, ref.X, 1e-13, 'bootstrap X');
assert_close(info.standard_errors, ref.standard_errors, 1e-12, 'bootstrap standard errors');
assert(info.bootstrap.replicates == 50, 'bootstrap replicates');
[X, info] = spdfit.fit(A, B, 'spd-tls', 'Bootstrap', 50, 'Seed', 3, 'Confidence', 0.9, 'Interval', 'basic');
ref = cli_json(cli, sprintf('fit --method spd-tls --bootstrap 50 --seed 3 --confidence 0.9 --interval basic --json "%s" "%s"', ...
                            fullfile(work, 'A.csv'), fullfile(work, 'B.csv')));
assert(strcmp(info.interval.type, 'basic') && strcmp(ref.interval.type, 'basic'), 'basic interval type');
assert_close(info.interval.lower, ref.interval.lower, 1e-12, 'basic interval');

% The noise model: rest rows and covariances as matrices, standard deviations as numbers, against
% the CLI's files and lists.
t = (1:200)';
RA = 0.01 * [sin(3.1 * t), cos(1.7 * t), sin(5.3 * t + 2)];
RB = [5, -2, 1] + [0.3 * cos(2.3 * t), 0.1 * sin(4.1 * t), 0.2 * cos(0.9 * t + 1)];
write_csv(fullfile(work, 'RA.csv'), RA);
write_csv(fullfile(work, 'RB.csv'), RB);
[X, info] = spdfit.fit(A, B, 'spd-tls', 'RestA', RA, 'RestB', RB);
ref = cli_json(cli, sprintf('fit --method spd-tls --rest-a "%s" --rest-b "%s" --json "%s" "%s"', ...
                            fullfile(work, 'RA.csv'), fullfile(work, 'RB.csv'), fullfile(work, 'A.csv'), ...
                            fullfile(work, 'B.csv')));
assert_close(X, ref.X, 1e-12, 'fit with rest rows');
assert(strcmp(info.diagnostics.noise_model.source, 'rest'), 'the noise model''s source');
assert_close(info.diagnostics.noise_model.cov_b, cov(RB), 1e-12, 'Sigma_B from the rest rows');
[X, info] = spdfit.fit(A, B, 'auto', 'NoiseStdA', [0.01 0.02 0.03], 'NoiseStdB', 0.1);
ref = cli_json(cli, sprintf('fit --method auto --noise-std-a 0.01,0.02,0.03 --noise-std-b 0.1 --json "%s" "%s"', ...
                            fullfile(work, 'A.csv'), fullfile(work, 'B.csv')));
assert_close(X, ref.X, 1e-12, 'fit with standard deviations');
assert(strcmp(info.diagnostics.noise_model.source, 'std'), 'the std source');
X = spdfit.fit(A, B, 'psd-ls', 'NoiseCovA', zeros(3), 'NoiseCovB', diag([1 4 9]));
Xw = spdfit.fit(A, B, 'psd-ls', 'NoiseStdA', 0, 'NoiseStdB', [1 2 3]);
assert_close(X, Xw, 1e-12, 'covariances as matrices equal the same standard deviations');
expect_error(@() spdfit.fit(A, B, 'spd-tls', 'RestA', RA), 'spdfit:UsageError', 'RestB');
expect_error(@() spdfit.fit(A, B, 'spde', 'NoiseStdA', 0.1, 'NoiseStdB', 0.1), 'spdfit:UsageError', 'spd-tls');
expect_error(@() spdfit.fit(A, B, 'spd-tls', 'NoiseStdA', 0.1, 'NoiseStdB', 0.1, 'NoiseRatio', 2), ...
             'spdfit:UsageError', 'NoiseRatio');
expect_error(@() spdfit.fit(A, B, 'spd-tls', 'RestA', RA(:, 1:2), 'RestB', RB), 'spdfit:DataError', 'RestA');

% nearest, its corr and keep-diagonal repairs.
C = [2 -1 0 0; -1 2 -1 0; 0 -1 2 -1; 0 0 -1 2] - 0.9 * ones(4) + 0.9 * eye(4);
C(1, 4) = 0.95; C(4, 1) = 0.95;
write_csv(fullfile(work, 'C.csv'), C);
cases = {{}, ''; {'Corr', true}, '--corr'; {'MinEigRel', 1e-6}, '--min-eig-rel 1e-6'};
for k = 1:size(cases, 1)
  [X, info] = spdfit.nearest(C, cases{k, 1}{:});
  ref = cli_json(cli, sprintf('nearest %s --json "%s"', cases{k, 2}, fullfile(work, 'C.csv')));
  assert_close(X, ref.X, 1e-13, ['nearest ' cases{k, 2}]);
  assert(abs(info.distance - ref.distance) <= 1e-13 * max(1, ref.distance), 'nearest distance');
end

% nearest's structured repairs: a mask (1-based pairs as in MATLAB), H weights, rank, factors,
% each against the command line on the same files, on C's correlation matrix R (C's kept entry
% -1.9 with a unit diagonal has no semidefinite completion).
R = C / 2;
write_csv(fullfile(work, 'R.csv'), R);
mask = zeros(4); mask(1, 2) = 1; mask(2, 1) = 1;
H = [1 2 1 1; 2 1 0.5 0; 1 0.5 1 1; 1 0 1 1];
write_csv(fullfile(work, 'mask.csv'), mask);
write_csv(fullfile(work, 'H.csv'), H);
Xp = spdfit.nearest(R, 'Corr', true, 'Fixed', [1 2]);
Xm = spdfit.nearest(R, 'Corr', true, 'Fixed', mask);
assert(isequal(Xp, Xm) && Xp(1, 2) == R(1, 2), 'nearest Fixed: pairs and mask, the entry kept');
ref = cli_json(cli, sprintf('nearest --corr --fixed "%s" --json "%s"', fullfile(work, 'mask.csv'), fullfile(work, 'R.csv')));
assert_close(Xm, ref.X, 1e-13, 'nearest Fixed');
[Xh, info] = spdfit.nearest(R, 'Corr', true, 'HWeights', H);
ref = cli_json(cli, sprintf('nearest --corr --h-weights "%s" --json "%s"', fullfile(work, 'H.csv'), fullfile(work, 'R.csv')));
assert_close(Xh, ref.X, 1e-13, 'nearest HWeights');
% A bound to the augmented Lagrangian's tolerance (tests/unit/test_nearest_structured.cpp).
assert(info.lower_bound <= info.distance * (1 + 1e-9), 'nearest HWeights lower bound');
[Xr, info] = spdfit.nearest(R, 'Corr', true, 'Rank', 2);
assert(rank(Xr, 1e-10) == 2 && numel(info.starts) == 5, 'nearest Rank');
F = spdfit.nearest(R, 'Corr', true, 'Factors', 2, 'FactorsOnly', true);
[~, info] = spdfit.nearest(R, 'Corr', true, 'Factors', 2);
assert_close(F, info.F, 0, 'nearest FactorsOnly returns F');
expect_error(@() spdfit.nearest(R, 'Corr', true, 'Rank', 2, 'Fixed', [1 2]), 'spdfit:UsageError', 'Rank');
expect_error(@() spdfit.nearest(R, 'Corr', true, 'Fixed', 0.5 * ones(4)), 'spdfit:DataError', 'Fixed');
expect_error(@() spdfit.nearest(R, 'Corr', true, 'Rank', 5), 'spdfit:DataError', 'Rank');

% solve, with a rank-deficient A.
As = [1 2 3; 2 4 6; 1 0 1; 0 1 1];
bs = [6; 12; 2; 2];
write_csv(fullfile(work, 'As.csv'), As);
write_csv(fullfile(work, 'bs.csv'), bs);
[x, info] = spdfit.solve(As, bs);
ref = cli_json(cli, sprintf('solve --json "%s" "%s"', fullfile(work, 'As.csv'), fullfile(work, 'bs.csv')));
assert_close(x, ref.solution, 1e-13, 'solve');
assert(info.rank == ref.rank, 'solve rank');
assert_close(spdfit.solve(As, bs'), x, 0, 'solve with b as a row');

% spdfit.hexapod.identify against `spdfit hexapod identify --json`, with a truth, a bootstrap and the
% physical fit from the built-in geometry.
examples = fullfile(getenv('SPDFIT_SOURCE_DIR'), 'examples', 'hexapod');
Ah = dlmread(fullfile(examples, 'A.csv'), ',', 2, 0);
Bh = dlmread(fullfile(examples, 'B.csv'), ',', 2, 0);
Mh = dlmread(fullfile(examples, 'truth.csv'), ',', 1, 0);
geometry = fullfile(work, 'G.json');
[status, ~] = system(sprintf('"%s" hexapod model --write-geometry "%s" > /dev/null 2>&1', cli, geometry));
assert(status == 0, 'hexapod model --write-geometry');
[result, text] = spdfit.hexapod.identify(Ah, Bh, 'Truth', Mh, 'Physical', true, 'Geometry', geometry, ...
                                         'Bootstrap', 20, 'Seed', 2);
ref = cli_json(cli, sprintf(['hexapod identify --truth "%s" --physical --geometry "%s" --bootstrap 20 ' ...
                             '--seed 2 --json "%s" "%s"'], fullfile(examples, 'truth.csv'), geometry, ...
                            fullfile(examples, 'A.csv'), fullfile(examples, 'B.csv')));
names = fieldnames(ref.methods);
for k = 1:numel(names)
  assert_close(result.methods.(names{k}).X, ref.methods.(names{k}).X, 1e-12, ['identify ' names{k}]);
end
assert_close(result.physical.M_p, ref.physical.M_p, 1e-10, 'identify: the physical M_p');
assert(abs(result.physical.mass - ref.physical.mass) <= 1e-10 * ref.physical.mass, 'identify: the mass');
assert(~isempty(strfind(text, 'physical')) || ~isempty(strfind(text, 'Physical')), 'identify: the text report');
expect_error(@() spdfit.hexapod.identify(Ah, Bh, 'Physical', true), 'spdfit:UsageError', 'Geometry');
expect_error(@() spdfit.hexapod.identify(Ah, Bh, 'StrutMasses', 'common'), 'spdfit:UsageError', 'Physical');
% One spelling of a setting: 'Consistent', false is the command line's --unconstrained.
expect_error(@() spdfit.hexapod.identify(Ah, Bh, 'Unconstrained', true), 'spdfit:UsageError', 'no option');
% A noise model the data refuse is a data error, as on the command line (exit 1).
expect_error(@() spdfit.fit(A, B, 'spd-tls', 'NoiseCovA', [1 2 0; 2 1 0; 0 0 1], 'NoiseCovB', eye(3)), ...
             'spdfit:DataError', 'NoiseCovA');
% The stiffness as one number for every strut, as the command line takes it.
[result_k] = spdfit.hexapod.identify(Ah, Bh, 'Stiffness', 2e6);
Xk = result_k.methods.spd_tls.X;
assert_close(sort(result_k.methods.spd_tls.modes_hz(:)), sort(sqrt(eig(Xk \ (2e6 * eye(6)))) / (2 * pi)), 1e-9, ...
             'identify: a scalar stiffness');
assert(~isempty(strfind(help('spdfit.hexapod.identify'), '''Geometry''')), 'help spdfit.hexapod.identify');
% One stiffness per strut (a vector), as the command line's --stiffness k1,...,k6.
kv = [1 2 3 4 5 6] * 1e6;
result_v = spdfit.hexapod.identify(Ah, Bh, 'Stiffness', kv);
assert_close(sort(result_v.methods.spd_tls.modes_hz(:)), sort(sqrt(eig(Xk \ diag(kv)))) / (2 * pi), 1e-9, ...
             'identify: a stiffness per strut');
% MATLAB's words in the help, not the command line's or Python's (issue 45 item 3).
for f = {'spdfit.fit', 'spdfit.hexapod.identify', 'spdfit.nearest'}
  h = help(f{1});
  for w = {'comma-separated)', 'None', 'True', 'False'}
    assert(isempty(regexp(h, ['(?<![A-Za-z_])' regexptranslate('escape', w{1}) '(?![A-Za-z_])'], 'once')), ...
           sprintf('help %s says "%s"', f{1}, w{1}));
  end
end
% Units (issue 42 item 2): B logged in kN with 'ScaleB', 1000 is the fit of B in N; a noise
% model in the file's units is scaled with it.
assert_close(spdfit.fit(A, B / 1000, 'spd-tls', 'ScaleB', 1000), spdfit.fit(A, B, 'spd-tls'), 1e-9, 'ScaleB');
assert_close(spdfit.fit(A / 2, B / 1000, 'spd-tls', 'ScaleA', [2 2 2], 'ScaleB', 1000, 'NoiseStdA', 0.05, ...
                        'NoiseStdB', 1e-4), ...
             spdfit.fit(A, B, 'spd-tls', 'NoiseStdA', 0.1, 'NoiseStdB', 0.1), 1e-9, 'ScaleA with a noise model');
expect_error(@() spdfit.fit(A, B, 'ls', 'ScaleB', [1 2]), 'spdfit:UsageError', 'ScaleB');
% Offsets (issue 42 item 1): 'estimate' is the fit of the centred data, info.offsets.c the
% constants of A X + 1 c' ~= B; 'rest' the fit of the data less the rest rows' means.
[Xo, io] = spdfit.fit(A + 100, B - 50, 'spd-tls', 'Offsets', 'estimate');
assert_close(Xo, spdfit.fit(A - mean(A), B - mean(B), 'spd-tls'), 1e-9, 'Offsets estimate');
assert(strcmp(io.offsets.mode, 'estimate'), 'info.offsets.mode');
assert_close(io.offsets.c(:)', mean(B - 50) - mean(A + 100) * Xo, 1e-9, 'info.offsets.c');
[Xr, ir] = spdfit.fit(A, B, 'spd-tls', 'RestA', RA, 'RestB', RB, 'Offsets', 'rest');
assert_close(Xr, spdfit.fit(A - mean(RA), B - mean(RB), 'spd-tls', 'RestA', RA, 'RestB', RB), 1e-9, ...
             'Offsets rest');
assert_close(ir.offsets.b(:)', mean(RB), 1e-12, 'info.offsets.b');
expect_error(@() spdfit.fit(A, B, 'ls', 'Offsets', 'rest'), 'spdfit:UsageError', 'rest');
% Robust (issue 42 item 3): gross errors in two rows of B are down-weighted, the fit is the clean one's.
Bg = B;
Bg([5 27], :) = Bg([5 27], :) + 50;
[Xh, ih] = spdfit.fit(A, Bg, 'ls', 'Robust', 'huber');
assert(strcmp(ih.robust.method, 'huber') && all(ismember([5 27], ih.robust.rows_downweighted)), 'info.robust');
assert_close(Xh, spdfit.fit(A, B, 'ls'), 0.05, 'Robust huber');
expect_error(@() spdfit.fit(A, B, 'spde', 'Robust', 'huber'), 'spdfit:UsageError', 'spde');
% Issue 45 item 5's messages through MATLAB: too few rest rows say so, a subnormal standard
% deviation is a number, NaN in a matrix to repair is named by its entry. Too few rest rows are
% the data's shortcoming: spdfit:DataError (spdfit:UsageError before 2026-12-02).
expect_error(@() spdfit.fit(A, B, 'spd-tls', 'RestA', RA(1:3, :), 'RestB', RB(1:3, :)), 'spdfit:DataError', ...
             'record more rest rows: at least 4');
spdfit.fit(A, B, 'ls', 'NoiseStdA', 0, 'NoiseStdB', 1e-308);
Cn = [1 0.5 NaN; 0.5 1 0.2; NaN 0.2 1];
expect_error(@() spdfit.nearest(Cn, 'Corr', true), 'spdfit:DataError', 'C(3,1) is NaN');

% Input types: single, integers and logical convert; a row vector A with a row vector B is one
% variable.
X = spdfit.fit(A, B, 'ls');
assert_close(spdfit.fit(single(A), single(B), 'ls'), X, 1e-6, 'single');
Ai = int32(round(10 * A));
Bi = int32(round(10 * B));
assert_close(spdfit.fit(Ai, Bi, 'ls'), spdfit.fit(double(Ai), double(Bi), 'ls'), 0, 'int32');
assert_close(spdfit.fit(uint8(abs(Ai)), uint8(abs(Bi)), 'ls'), spdfit.fit(abs(double(Ai)), abs(double(Bi)), 'ls'), ...
             0, 'uint8');
L = logical(mod(reshape(1:60, 20, 3), 2));
assert_close(spdfit.fit(L, double(L) * 2 + [L(2:end, :); L(1, :)] * 0.1, 'ls'), ...
             spdfit.fit(double(L), double(L) * 2 + double([L(2:end, :); L(1, :)]) * 0.1, 'ls'), 0, 'logical');
a = (1:10) / 3;
assert_close(spdfit.fit(a, 2 * a, 'ls'), 2, 1e-14, 'row vectors');
assert_close(spdfit.fit(A, B, "spde"), spdfit.fit(A, B, 'spde'), 0, 'a string method');

% Errors and their identifiers.
expect_error(@() spdfit.fit(sparse(A), B), 'spdfit:UsageError', 'sparse');
expect_error(@() spdfit.fit(A + 1i, B), 'spdfit:UsageError', 'complex');
expect_error(@() spdfit.fit({A}, B), 'spdfit:UsageError', 'cell');
An = A; An(3, 2) = NaN;
expect_error(@() spdfit.fit(An, B), 'spdfit:DataError', 'A(3,2) is NaN');
Bn = B; Bn(5, 1) = Inf;
expect_error(@() spdfit.fit(A, Bn), 'spdfit:DataError', 'B(5,1) is Inf');
expect_error(@() spdfit.fit([], B), 'spdfit:DataError', 'A is empty');
expect_error(@() spdfit.fit(A, B(1:end - 1, :)), 'spdfit:DataError', 'rows');
expect_error(@() spdfit.fit(A, B, 'nosuch'), 'spdfit:UsageError', 'unknown method');
expect_error(@() spdfit.fit(A, B, 'spde', 'NoSuchOption', 1), 'spdfit:UsageError', 'no option');
expect_error(@() spdfit.fit(A, B, 'spde', 'Bootstrap'), 'spdfit:UsageError', 'name-value pairs');
expect_error(@() spdfit.fit(A, B, 'spde', 'Bootstrap', 2.5), 'spdfit:UsageError', 'integer');
expect_error(@() spdfit.fit(A, B, 'spde', 'Confidence', 0.9), 'spdfit:UsageError', 'Bootstrap');
expect_error(@() spdfit.fit(A, B, 'spde', 'Interval', 'basic'), 'spdfit:UsageError', 'Bootstrap');
expect_error(@() spdfit.fit(A, B, 'spde', 'Bootstrap', 10, 'Interval', 'bca'), 'spdfit:UsageError', 'percentile');
expect_error(@() spdfit.fit(A, B, 'ls', 'MaxIterations', 10), 'spdfit:UsageError', 'MaxIterations');
expect_error(@() spdfit.fit(A, B, 'spd-tls', 'MaxIterations', -1), 'spdfit:UsageError', 'MaxIterations');
expect_error(@() spdfit.nearest(C, 'Corr', 'yes'), 'spdfit:UsageError', 'Corr');
expect_error(@() spdfit.nearest(C, 'KeepDiag', true, 'ViaCorr', true), 'spdfit:UsageError', 'KeepDiag');
expect_error(@() spdfit.nearest(C, 'Alpha', 0.1), 'spdfit:UsageError', 'Alpha');
expect_error(@() spdfit.solve(As, [1; 2]), 'spdfit:DataError', 'rows');
expect_error(@() spdfit.solve(As, bs, 'Threshold', -1), 'spdfit:UsageError', 'Threshold');
% Option names are not case-sensitive; [] is the default.
assert_close(spdfit.fit(A, B, 'spd-tls', 'maxiterations', 300), spdfit.fit(A, B, 'spd-tls'), 0, 'case');
assert_close(spdfit.fit(A, B, 'spd-tls', 'RankTolerance', []), spdfit.fit(A, B, 'spd-tls'), 0, '[] default');

% Warnings carry identifiers, so that users can silence them.
Ar = [A(:, 1), A(:, 1), A(:, 3)];
state = warning();
restore = onCleanup(@() warning(state));
expect_warning(@() spdfit.fit(Ar, B, 'ls'), 'spdfit:rankDeficient');
expect_warning(@() spdfit.nearest([1 2; 2 1]), 'spdfit:eigenvaluesRaised');
expect_warning(@() spdfit.nearest([4 1; 1 0], 'KeepDiag', true, 'MinDiag', 1e-3), 'spdfit:diagonalChanged');
% Method names in any case, as option names (issue 45).
assert_close(spdfit.fit(A, B, 'SPD-TLS'), spdfit.fit(A, B, 'spd-tls'), 0, 'SPD-TLS');
assert_close(spdfit.fit(A, B, 'Ls'), spdfit.fit(A, B, 'ls'), 0, 'Ls');
% ... and no "called from" trace (they are about the data), with the backtrace setting kept.
warning('on', 'backtrace');
printed = evalc('spdfit.fit(Ar, B, ''ls'');');
assert(~isempty(strfind(printed, 'rank-deficient')) && isempty(strfind(printed, 'called from')), printed);
kept = warning('query', 'backtrace');
assert(strcmp(kept.state, 'on'), 'spdfit.fit changed the backtrace setting');
% Silenced by its identifier, a warning is not raised (and the result still lists it).
warning('off', 'spdfit:eigenvaluesRaised');
lastwarn('', '');
[~, info] = spdfit.nearest([1 2; 2 1]);
[~, id] = lastwarn();
assert(isempty(id) && ~isempty(info.warnings), 'a silenced warning');
warning(state);

% Help from the M-files, with the option table's options.
text = help('spdfit.fit');
assert(~isempty(strfind(text, '''Bootstrap''')) && ~isempty(strfind(text, '''MaxIterations''')), 'help spdfit.fit');
assert(isempty(strfind(text, '''Stream''')), 'help spdfit.fit lists the stream''s options');
assert(~isempty(strfind(text, '''RestA'' (matrix')) && ~isempty(strfind(text, '''NoiseStdB''')), 'help: noise options');
assert(~isempty(strfind(help('spdfit.nearest'), '''KeepDiag''')), 'help spdfit.nearest');
assert(~isempty(strfind(help('spdfit.solve'), '''Threshold''')), 'help spdfit.solve');

% A large fit, 100 times: it completes and memory does not grow across calls.
m = 1e6;
Al = sin((1:m)' * [0.37, 1.1, 2.3, 0.71, 1.9, 2.9]);
Bl = Al * (eye(6) + 0.1);
Xl = spdfit.fit(Al, Bl, 'spde');
assert(norm(Xl - (eye(6) + 0.1), 'fro') < 1e-9, 'the large fit');
before = resident_kib();
for k = 1:100
  spdfit.fit(Al, Bl, 'ls');
end
growth = resident_kib() - before;
assert(growth < 20 * 1024, sprintf('memory grew by %d KiB over 100 fits of %d x 6', growth, m));

% The MEX links no file reader (libmatio, HDF5): it is a core without them, as MATLAB needs.
[status, dynamic] = system(['readelf -d "' getenv('SPDFIT_MEX') '"']);
assert(status == 0, 'readelf');
assert(isempty(strfind(dynamic, 'matio')) && isempty(strfind(dynamic, 'hdf5')), ['the MEX links: ' dynamic]);
assert(isempty(strfind(dynamic, 'libstdc++')), 'the MEX links libstdc++ dynamically');
% The contradiction check can fail: it flags the warning auto's psd-ls printed before issue 45.
assert(numel(contradicting_lines({'warning: psd-ls models noise in B only (weighted by RestB)'}, true, true)) == 1);
assert(isempty(contradicting_lines({'warning: auto: spde ran without the noise model'}, true, true)));
% spdfit.payload.identify on the example log's static poses (t from 1 to 3.39 s, the rows the
% command line takes with --time-col t --rows 1:3.39) against `spdfit payload identify --json`.
log = fullfile(getenv('SPDFIT_SOURCE_DIR'), 'examples', 'payload', 'log.csv');
data = dlmread(log, ',', 1, 0);
static = data(:, 1) >= 1 & data(:, 1) <= 3.39;
payload = spdfit.payload.identify(data(static, 2:7), 'Quaternion', data(static, 8:11));
ref = cli_json(cli, ['payload identify "' log '" --wrench-cols fx:tz --quat-cols qx:qw --time-col t ' ...
                     '--rows 1:3.39 --json']);
assert(payload.samples == ref.samples && payload.samples == 240, 'payload samples');
assert_close(payload.mass, ref.mass, 1e-10, 'payload mass');
assert_close(payload.center_of_mass(:), ref.center_of_mass(:), 1e-10, 'payload centre of mass');
assert_close(payload.force_bias(:), ref.force_bias(:), 1e-10, 'payload force bias');
assert_close(payload.torque_bias(:), ref.torque_bias(:), 1e-10, 'payload torque bias');
assert(abs(payload.mass - 1.2) < 0.01, 'payload mass against the truth (1.2 kg)');
expect_error(@() spdfit.payload.identify(data(static, 2:6), 'Quaternion', data(static, 8:11)), ...
             'spdfit:DataError', 'must give 6 columns');

% docs/matlab.md's examples run as written, with no warning against the method chosen.
run_doc_examples(fullfile(getenv('SPDFIT_SOURCE_DIR'), 'docs', 'matlab.md'));
run_doc_examples(fullfile(getenv('SPDFIT_SOURCE_DIR'), 'README.md'));
disp('test_spdfit_mex: all passed');
end

function [A, B] = sample_data()
% Deterministic data (no random state to record): 40 samples of a 3x3 SPD X, both sides perturbed.
m = 40;
M = [4 1 0.5; 1 3 0.2; 0.5 0.2 2];
A = [sin((1:m)' * 0.7), cos((1:m)' * 1.3), sin((1:m)' * 2.9 + 1)];
B = A * M + 0.01 * cos((1:m)' * [5.1, 3.7, 8.3]);
A = A + 0.01 * sin((1:m)' * [4.3, 9.1, 6.7]);
end

function write_csv(path, X)
f = fopen(path, 'w');
for i = 1:size(X, 1)
  fprintf(f, '%s\n', strjoin(arrayfun(@(v) sprintf('%.17g', v), X(i, :), 'UniformOutput', false), ','));
end
fclose(f);
end

function doc = cli_json(cli, args)
[status, out] = system(['"' cli '" ' args ' 2>/dev/null']);
assert(status == 0, sprintf('spdfit %s exited %d', args, status));
doc = jsondecode(out);
end

function assert_close(actual, expected, rel, what)
assert(isequal(size(actual), size(expected)), sprintf('%s: size %s, expected %s', what, mat2str(size(actual)), ...
                                                      mat2str(size(expected))));
scale = max(1, norm(expected(:), Inf));
err = norm(actual(:) - expected(:), Inf);
assert(err <= rel * scale, sprintf('%s: differs by %g (relative tolerance %g)', what, err / scale, rel));
end

function assert_same_fields(info, ref, what)
missing = setdiff(fieldnames(info), fieldnames(ref));
assert(isempty(missing), sprintf('%s: fields not in the CLI''s JSON: %s', what, strjoin(missing', ', ')));
missing = setdiff(fieldnames(ref), fieldnames(info));
assert(isempty(missing), sprintf('%s: CLI JSON fields not in info: %s', what, strjoin(missing', ', ')));
end

function expect_error(f, id, part)
try
  f();
catch err
  assert(strcmp(err.identifier, id), sprintf('expected %s (%s), got %s: %s', id, part, err.identifier, err.message));
  assert(~isempty(strfind(err.message, part)), sprintf('message "%s" does not say "%s"', err.message, part));
  assert(isempty(strfind(err.message, 'spdfit_mex')), ['message names the MEX: ' err.message]);
  return;
end
error('no error raised (expected %s: %s)', id, part);
end

function expect_warning(f, id)
% Only `id` is on, so that lastwarn is the warning the call raised with that identifier.
state = warning();
warning('off', 'all');
warning('on', id);
lastwarn('', '');
f();
[~, got] = lastwarn();
warning(state);
assert(strcmp(got, id), sprintf('expected the warning %s, got "%s"', id, got));
end

function remove_folder(path)
confirm_recursive_rmdir(false);
rmdir(path, 's');
end

function kib = resident_kib()
text = fileread('/proc/self/status');
token = regexp(text, 'VmRSS:\s*(\d+)', 'tokens', 'once');
kib = str2double(token{1});
end

function run_doc_examples(page)
% Every ```matlab block of the page, in order, in one workspace of its own.
text = fileread(page);
blocks = regexp(text, '```matlab\n(.*?)```', 'tokens');
assert(~isempty(blocks), ['no examples in ' page]);
for k = 1:numel(blocks)
  try
    printed = evalc(blocks{k}{1});
  catch err
    error('%s, example %d: %s', page, k, err.message);
  end
  % A fit's warnings (evalc captures them) agree with the method it chose and its noise model.
  if ~isempty(strfind(blocks{k}{1}, 'info] = spdfit.fit(')) && isfield(info, 'diagnostics')
    d = info.diagnostics;
    bad = contradicting_lines(strsplit(printed, "\n"), isfield(d, 'reason') && ~isempty(d.reason), ...
                              isfield(d, 'noise_model') && ~isempty(d.noise_model));
    assert(isempty(bad), sprintf('%s, example %d: contradicts its method or noise model: %s', page, k, ...
                                 strjoin(bad, ' | ')));
  end
end
end

function bad = contradicting_lines(lines, chosen_by_auto, noise_model)
% The rules of tests/support/spdfit_testing.py's contradicting_warnings: with a method chosen by
% auto, no line calls it biased, says it ignores the model's noise in A or recommends auto; with a
% noise model, no line states the equal-noise model's view.
against_auto = {'is biased', 'models noise in B only', '(or auto)', 'use auto'};
against_model = {'cannot tell A''s from B''s', 'in every entry of A'};
bad = {};
for i = 1:numel(lines)
  hits = @(words) any(cellfun(@(w) ~isempty(strfind(lines{i}, w)), words));
  if (chosen_by_auto && hits(against_auto)) || (noise_model && hits(against_model))
    bad{end + 1} = lines{i};
  end
end
end
