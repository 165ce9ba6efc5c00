// core/batch_plan (docs/batch.md): --shard K/N slices of an input list are disjoint and together
// cover it exactly once, whatever order the list came in; parsing refuses what is not K/N with
// 0 <= K < N; durations and the ETA read as documented.
#include "core/batch_plan.h"

#include <QtTest>
#include <algorithm>
#include <random>
#include <set>

using namespace velvet;

class TestBatchPlan : public QObject {
    Q_OBJECT
private slots:
    void shardsAreDisjointAndCover() {
        std::vector<std::string> inputs;
        for (int i = 0; i < 103; ++i)
            inputs.push_back("lib/m" + std::to_string(i * 7919 % 1000) + ".json");
        inputs.push_back(inputs[5]); // a duplicate is one input
        for (int n : {1, 2, 3, 7, 16, 103, 200}) {
            std::multiset<std::string> seen;
            std::vector<std::string> shuffled = inputs;
            std::mt19937 rng{static_cast<unsigned>(n)};
            size_t largest = 0, smallest = inputs.size();
            for (int k = 0; k < n; ++k) {
                // Each machine may get the list in another order: the slice must not change.
                std::shuffle(shuffled.begin(), shuffled.end(), rng);
                const auto slice = shardInputs(shuffled, {k, n});
                QCOMPARE(slice, shardInputs(inputs, {k, n}));
                seen.insert(slice.begin(), slice.end());
                largest = std::max(largest, slice.size());
                smallest = std::min(smallest, slice.size());
            }
            const std::set<std::string> unique(inputs.begin(), inputs.end());
            QCOMPARE(seen.size(), unique.size()); // no input twice over all shards
            QVERIFY(std::equal(unique.begin(), unique.end(),
                               std::set<std::string>(seen.begin(), seen.end()).begin()));
            QVERIFY(largest - smallest <= 1); // round-robin: balanced slices
        }
    }

    void parseShardRefusesWhatIsNotKOfN() {
        QCOMPARE(parseShard("0/1")->count, 1);
        QCOMPARE(parseShard("3/8")->index, 3);
        QCOMPARE(parseShard("7/8")->count, 8);
        for (const char* bad : {"8/8", "-1/4", "1", "1/0", "a/b", "1/2/3", "", "/4", "2/", " 1/4"})
            QVERIFY2(!parseShard(bad), bad);
    }

    void durationsAndEta() {
        QCOMPARE(formatDuration(0), std::string("0:00"));
        QCOMPARE(formatDuration(6.2), std::string("0:07"));
        QCOMPARE(formatDuration(754), std::string("12:34"));
        QCOMPARE(formatDuration(3723), std::string("1:02:03"));
        QVERIFY(!estimateRemaining(0, 10, 5.0));
        QCOMPARE(*estimateRemaining(2, 10, 4.0), 16.0); // 2 s each, 8 left
        QCOMPARE(*estimateRemaining(10, 10, 4.0), 0.0);
    }
};

QTEST_APPLESS_MAIN(TestBatchPlan)
#include "test_core_batch_plan.moc"
