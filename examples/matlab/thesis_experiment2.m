function result = thesis_experiment2(trials, seed)
%THESIS_EXPERIMENT2  The thesis' Experiment 2 (chapter 6) as a Monte Carlo experiment, with spdfit.
%   RESULT = THESIS_EXPERIMENT2(TRIALS, SEED) repeats the thesis' simulation TRIALS times (default
%   300) from the random state SEED (default 1): the M-file's generator, unchanged (m = 12 samples
%   of 6 strut accelerations, uniform of width 10; noise uniform of width nm = 3.2 in every entry of
%   A and B, variance nm^2/12 = 0.853), with the thesis' own estimator code (lyap, the SVD's V12
%   and V22, the Riccati solution) replaced by spdfit.fit calls. RESULT.(method) holds the mean,
%   the standard error, the standard deviation and the median of ||Mprel - Mest||_F.
%
%   The thesis' table is one draw of an unrecorded rand state; compare the means instead, with
%   `spdfit experiment thesis --noise-var 0.8533 --trials 300 --json`, within their standard errors
%   (tests/matlab/test_thesis_experiment.m does).
if nargin < 1, trials = 300; end
if nargin < 2, seed = 1; end
rand('state', seed);
m = 12;       % the number of samples
n = 6;        % the number of variables
nm = 3.2;     % the noise's width: variance nm^2/12
% Mprel: the ideal joint-space mass-inertia matrix (thesis eq. 6.1).
Mprel = [4.6881  0.1978 -0.4042  1.7981 -0.4046  0.6110
         0.1978  4.6881  0.6110 -0.4046  1.7981 -0.4042
        -0.4042  0.6110  4.6881  0.1975 -0.4042  1.7984
         1.7981 -0.4046  0.1975  4.6881  0.6114 -0.4042
        -0.4046  1.7981 -0.4042  0.6114  4.6881  0.1975
         0.6110 -0.4042  1.7984 -0.4042  0.1975  4.6881];
methods = {'ls', 'procrustes', 'tls', 'tls-sym', 'tls-psd', 'spde'};
errors = zeros(trials, numel(methods));
for t = 1:trials
  % The thesis' M-file: payload accelerations, their measurement, the base forces, theirs.
  lddot = 10 .* (rand([m, n]) - 0.5 .* ones([m, n]));
  lddotm = lddot + nm * (rand([m, n]) - 0.5 .* ones([m, n]));
  fb = lddot * Mprel;
  fbm = fb + nm * (rand([m, n]) - 0.5 .* ones([m, n]));
  for k = 1:numel(methods)
    Mest = spdfit.fit(lddotm, fbm, methods{k});
    errors(t, k) = norm(Mprel - Mest, 'fro');
  end
end
result = struct();
for k = 1:numel(methods)
  e = errors(:, k);
  result.(strrep(methods{k}, '-', '_')) = struct('mean', mean(e), 'standard_error', std(e) / sqrt(trials), ...
                                                 'std', std(e), 'median', median(e));
end
if nargout == 0
  fprintf('Thesis Experiment 2 with spdfit.fit: %d trials, ||Mprel - Mest||_F\n', trials);
  fprintf('%-12s %8s %8s %8s\n', 'method', 'mean', '+- s.e.', 'median');
  for k = 1:numel(methods)
    r = result.(strrep(methods{k}, '-', '_'));
    fprintf('%-12s %8.4f %8.4f %8.4f\n', methods{k}, r.mean, r.standard_error, r.median);
  end
end
end
