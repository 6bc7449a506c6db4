// The median of a sample as the pipeline and the diagnosis take it: the element of rank n/2 in
// sorted order, so always one of the values. For an even count that is the upper of the two middle
// values, not their mean. An empty sample gives 0 (callers that cannot be empty need not check).
#pragma once

#include <vector>

namespace adahrs::common {

/// The element of rank values.size() / 2 (above); 0 for an empty sample. O(n) (nth_element).
double Median(std::vector<double> values);

}  // namespace adahrs::common
